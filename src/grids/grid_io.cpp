// Grid files: format detection, channel resolution and the entry points; the format-specific
// work is in grid_vdb_read.cpp, grid_vdb_write.cpp and grid_nvdb.cpp.
#include "grids/grid_io.h"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/atomic_file.h"
#include "grids/grid_io_internal.h"

namespace caligo {
namespace {

// OpenVDB files start with the 64-bit little-endian integer 0x56444220 ("VDB " backwards),
// NanoVDB files and buffers with "NanoVDB0".
constexpr unsigned char kOpenVdbMagic[8] = {0x20, 0x42, 0x44, 0x56, 0, 0, 0, 0};
constexpr unsigned char kNanoVdbMagic[8] = {'N', 'a', 'n', 'o', 'V', 'D', 'B', '0'};

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

std::string describe_grids(const std::vector<GridEntry>& entries) {
  if (entries.empty()) return "the file holds no grids";
  std::string list = "grids in the file:";
  for (const GridEntry& e : entries) list += " \"" + e.name + "\" (" + e.type + ")";
  return list;
}

bool accepts(GridValueKind kind, const std::string& type, GridFileFormat format) {
  // OpenVDB double grids are converted on read; a NanoVDB grid is used as stored.
  const bool vdb = format == GridFileFormat::kOpenVdb;
  switch (kind) {
    case GridValueKind::kFloat:
      return type == "float" || (vdb && type == "double");
    case GridValueKind::kVec3:
      return type == "vec3s" || (vdb && type == "vec3d");
  }
  return false;
}

const char* kind_name(GridValueKind kind) {
  switch (kind) {
    case GridValueKind::kFloat:
      return "a float grid";
    case GridValueKind::kVec3:
      return "a vec3 (vec3s) grid";
  }
  return "";
}

// One channel to find: the names to try in order, and whether the scene asked for it by name.
struct ChannelQuery {
  const char* channel;
  std::vector<std::string> names;
  bool required;
  GridValueKind kind;
};

std::optional<GridRequest> resolve(const ChannelQuery& q, const std::vector<GridEntry>& entries,
                                   GridFileFormat format, const std::string& path,
                                   const SourceLocation& where) {
  for (const std::string& name : q.names) {
    const auto it =
        std::find_if(entries.begin(), entries.end(), [&](const GridEntry& e) { return e.name == name; });
    if (it == entries.end()) continue;
    if (!accepts(q.kind, it->type, format))
      throw_grid_file_error(path, where,
                            std::string("the ") + q.channel + " grid \"" + name + "\" holds " + it->type +
                                " values; expected " + kind_name(q.kind));
    return GridRequest{name, q.kind};
  }
  if (q.required)
    throw_grid_file_error(path, where,
                          std::string("has no ") + q.channel + " grid named \"" + q.names.front() + "\" (" +
                              describe_grids(entries) + ")");
  return std::nullopt;
}

ChannelQuery optional_query(const char* channel, const std::optional<std::string>& asked,
                            std::vector<std::string> defaults, GridValueKind kind) {
  if (asked) return {channel, {*asked}, true, kind};
  return {channel, std::move(defaults), false, kind};
}

}  // namespace

GridFileFormat grid_file_format(const std::string& path, const SourceLocation& where) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw_grid_file_error(path, where, "no such grid file");
  std::ifstream in(path, std::ios::binary);
  unsigned char magic[8] = {};
  if (!in || !in.read(reinterpret_cast<char*>(magic), sizeof(magic)))
    throw_grid_file_error(path, where, "cannot read the grid file (empty or unreadable)");
  const bool is_vdb = std::memcmp(magic, kOpenVdbMagic, 8) == 0;
  const bool is_nvdb = std::memcmp(magic, kNanoVdbMagic, 8) == 0;
  const std::string ext = lower_extension(path);
  if (ext == ".vdb" && !is_vdb)
    throw_grid_file_error(path, where, "not an OpenVDB file (wrong magic number)");
  if (ext == ".nvdb" && !is_nvdb)
    throw_grid_file_error(path, where, "not a NanoVDB file (wrong magic number)");
  if (is_vdb) return GridFileFormat::kOpenVdb;
  if (is_nvdb) return GridFileFormat::kNanoVdb;
  throw_grid_file_error(path, where, "neither an OpenVDB (.vdb) nor a NanoVDB (.nvdb) file");
}

NanoGrids read_grid_channels(const std::string& path, const GridChannels& channels,
                             const SourceLocation& where) {
  const GridFileFormat format = grid_file_format(path, where);
  const std::vector<GridEntry> entries =
      format == GridFileFormat::kOpenVdb ? list_vdb_grids(path, where) : list_nvdb_grids(path, where);
  const ChannelQuery queries[] = {
      {"density", {channels.density}, true, GridValueKind::kFloat},
      optional_query("temperature", channels.temperature, {"temperature"}, GridValueKind::kFloat),
      optional_query("flame", channels.flame, {"flame", "heat"}, GridValueKind::kFloat),
      optional_query("color", channels.color, {"Cd"}, GridValueKind::kVec3),
  };
  std::vector<GridRequest> requests;
  std::vector<int> slot_of_request;  // index into queries
  for (int q = 0; q < 4; ++q) {
    if (std::optional<GridRequest> r = resolve(queries[q], entries, format, path, where)) {
      requests.push_back(*r);
      slot_of_request.push_back(q);
    }
  }
  std::vector<NanoGridHandle> handles = format == GridFileFormat::kOpenVdb
                                            ? read_vdb_grids(path, requests, where)
                                            : read_nvdb_grids(path, requests, where);
  NanoGrids grids;
  for (size_t i = 0; i < handles.size(); ++i) {
    // In the order of `queries`: density, then the optional channels.
    std::optional<NanoGridHandle>* const optional_slots[] = {&grids.temperature, &grids.flame, &grids.color};
    if (slot_of_request[i] == 0)
      grids.density = std::move(handles[i]);
    else
      *optional_slots[slot_of_request[i] - 1] = std::move(handles[i]);
  }
  return grids;
}

std::shared_ptr<const VolumeGrid> load_grid_file(const std::string& path, const GridChannels& channels,
                                                 const SourceLocation& where) {
  return make_volume_grid(read_grid_channels(path, channels, where), where);
}

void write_grid_file(const std::string& path, const std::vector<SparseFloatGrid>& grids) {
  const std::string ext = lower_extension(path);
  if (ext != ".vdb" && ext != ".nvdb")
    throw InputError({path, ""}, "grid files must end in .vdb (OpenVDB) or .nvdb (NanoVDB)");
  if (grids.empty()) throw InputError({path, ""}, "no grids to write");
  write_file_atomically(path, [&](const std::string& temp) {
    if (ext == ".vdb")
      write_vdb_file(temp, grids);
    else
      write_nvdb_file(temp, grids);
    // OpenVDB's and NanoVDB's writers do not report a failed write (a full disk): read the
    // file back and compare before it replaces anything.
    GridFileInfo written;
    try {
      written = describe_grid_file(temp);
    } catch (const std::exception&) {
      throw std::runtime_error("the file written does not read back whole (is the disk full?)");
    }
    // Names, not voxel counts: the writers may prune or tile what a SparseFloatGrid holds.
    bool same = written.grids.size() == grids.size();
    for (const SparseFloatGrid& g : grids)
      same = same && std::any_of(written.grids.begin(), written.grids.end(),
                                 [&](const GridInfo& w) { return w.name == g.name; });
    if (!same) throw std::runtime_error("the written file does not hold the grids written (disk full?)");
  });
}

GridFileInfo describe_grid_file(const std::string& path) {
  const GridFileFormat format = grid_file_format(path, {});
  GridFileInfo info = format == GridFileFormat::kOpenVdb ? describe_vdb_file(path) : describe_nvdb_file(path);
  info.path = path;
  info.file_bytes = std::filesystem::file_size(path);
  return info;
}

}  // namespace caligo
