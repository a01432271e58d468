// NanoVDB files. nanovdb::io trusts its input (it allocates whatever a header says and reads
// name lengths straight into new[]), so segments are parsed here with every size checked
// against the file before anything is allocated, and every grid read is checked for pointers
// inside its buffer before NanoVDB's validator (checksums) and any traversal see it.
//
// File layout (nanovdb/util/IO.h): segments of { Header (16 B), gridCount x (MetaData (176 B)
// + name), gridCount x grid data }; we read uncompressed files only.
#include <iostream>  // GridValidator.h uses std::cerr without including it

#include <nanovdb/util/GridValidator.h>
#include <nanovdb/util/IO.h>

#include <filesystem>
#include <fstream>

#include "grids/grid_io_internal.h"

namespace caligo {
namespace {

constexpr uint32_t kMaxNameBytes = 4096;
constexpr uint32_t kMaxGridsPerSegment = 4096;

struct NvdbRecord {
  nanovdb::io::MetaData meta;
  std::string name;
  uint64_t data_offset = 0;  // of the grid's bytes in the file
};

const char* type_name(nanovdb::GridType type) {
  switch (type) {
    case nanovdb::GridType::Float:
      return "float";
    case nanovdb::GridType::Double:
      return "double";
    case nanovdb::GridType::Int32:
      return "int32";
    case nanovdb::GridType::Int64:
      return "int64";
    case nanovdb::GridType::Vec3f:
      return "vec3s";
    case nanovdb::GridType::Vec3d:
      return "vec3d";
    case nanovdb::GridType::Boolean:
      return "bool";
    case nanovdb::GridType::Mask:
      return "mask";
    default:
      return nanovdb::toStr(type < nanovdb::GridType::End ? type : nanovdb::GridType::Unknown);
  }
}

// nanovdb::Version::c_str() returns a malloc'ed buffer the caller must free; this does not.
std::string version_string(const nanovdb::Version& v) {
  return std::to_string(v.getMajor()) + "." + std::to_string(v.getMinor()) + "." + std::to_string(v.getPatch());
}

class NvdbReader {
 public:
  NvdbReader(const std::string& path, const SourceLocation& where) : path_(path), where_(where) {
    std::error_code ec;
    size_ = std::filesystem::file_size(path, ec);
    if (ec) fail("cannot read the NanoVDB file");
    in_.open(path, std::ios::binary);
    if (!in_) fail("cannot read the NanoVDB file");
  }

  [[noreturn]] void fail(const std::string& what) const { throw_grid_file_error(path_, where_, what); }

  std::vector<NvdbRecord> scan() {
    std::vector<NvdbRecord> records;
    uint64_t pos = 0;
    while (pos < size_) {
      nanovdb::io::Header header;
      read_at(pos, &header, sizeof(header), "segment header");
      pos += sizeof(header);
      if (header.magic != NANOVDB_MAGIC_NUMBER) fail("corrupt NanoVDB file (bad segment magic number)");
      if (header.version.getMajor() != NANOVDB_MAJOR_VERSION_NUMBER)
        fail("NanoVDB file version " + version_string(header.version) + " is not supported (expected " +
             std::to_string(NANOVDB_MAJOR_VERSION_NUMBER) + ".x)");
      // nanovdb::io::toStr indexes a table by the codec without a bounds check.
      if (header.codec >= nanovdb::io::Codec::END) fail("corrupt NanoVDB file (unknown codec)");
      if (header.codec != nanovdb::io::Codec::NONE)
        fail(std::string("compressed NanoVDB files (") + nanovdb::io::toStr(header.codec) +
             ") are not supported; write it uncompressed");
      if (header.gridCount == 0 || header.gridCount > kMaxGridsPerSegment)
        fail("corrupt NanoVDB file (grid count)");
      const size_t first = records.size();
      for (int i = 0; i < header.gridCount; ++i) {
        NvdbRecord r;
        read_at(pos, &r.meta, sizeof(r.meta), "grid header");
        pos += sizeof(r.meta);
        if (r.meta.nameSize == 0 || r.meta.nameSize > kMaxNameBytes)
          fail("corrupt NanoVDB file (grid name size)");
        std::string name(r.meta.nameSize, '\0');
        read_at(pos, name.data(), name.size(), "grid name");
        pos += r.meta.nameSize;
        r.name = name.c_str();  // stops at the stored terminator
        records.push_back(std::move(r));
      }
      for (size_t i = first; i < records.size(); ++i) {
        NvdbRecord& r = records[i];
        if (r.meta.gridSize != r.meta.fileSize || r.meta.gridSize < sizeof(nanovdb::GridData) ||
            r.meta.gridSize > size_ - std::min(size_, pos))
          fail("corrupt or truncated NanoVDB file (grid \"" + r.name + "\" claims " +
               std::to_string(r.meta.gridSize) + " bytes)");
        r.data_offset = pos;
        pos += r.meta.gridSize;
      }
    }
    if (records.empty()) fail("the NanoVDB file holds no grids");
    return records;
  }

  NanoGridHandle read_grid(const NvdbRecord& r) {
    nanovdb::HostBuffer buffer = nanovdb::HostBuffer::create(r.meta.gridSize);
    read_at(r.data_offset, buffer.data(), r.meta.gridSize, "grid \"" + r.name + "\"");
    NanoGridHandle handle(std::move(buffer));
    const nanovdb::GridMetaData* meta = handle.gridMetaData();
    // A buffer holds this one grid: GridHandle::grid() would step past its end, by the grid's
    // stated size, looking for a grid index other than 0.
    if (!meta->isValid() || meta->gridSize() != r.meta.gridSize || meta->gridType() != r.meta.gridType ||
        meta->gridIndex() != 0)
      fail("corrupt NanoVDB file (grid \"" + r.name + "\" disagrees with its header)");
    return handle;
  }

 private:
  void read_at(uint64_t pos, void* dst, uint64_t n, const std::string& what) {
    if (pos > size_ || n > size_ - pos) fail("truncated NanoVDB file (the " + what + " is cut off)");
    in_.seekg(std::streamoff(pos));
    if (!in_.read(static_cast<char*>(dst), std::streamsize(n))) fail("cannot read the " + what);
  }

  std::string path_;
  SourceLocation where_;
  uint64_t size_ = 0;
  std::ifstream in_;
};

// A node's child offsets (NanoVDB adds them to the node's address) all land inside
// [lo, lo + size), checked as numbers: a pointer sum that leaves the buffer, let alone one that
// wraps the address space, is undefined behaviour before anything is read.
template <typename NodeT>
bool child_offsets_inside(const NodeT& node, const uint8_t* lo, uint64_t size) {
  const int64_t at = reinterpret_cast<const uint8_t*>(&node) - lo;  // node is inside
  const auto inside = [&](int64_t offset) { return offset >= -at && offset <= int64_t(size) - at; };
  if constexpr (requires { node.data()->mTableSize; }) {  // the root: a table of tiles
    for (uint32_t n = 0; n < node.data()->mTableSize; ++n)
      if (!inside(node.data()->tile(n)->child)) return false;
  } else {  // an internal node: a child mask over a table of offsets or values
    for (uint32_t n = 0; n < NodeT::SIZE; ++n)
      if (node.data()->mChildMask.isOn(n) && !inside(node.data()->mTable[n].child)) return false;
  }
  return true;
}

// Every node a traversal can reach lies inside the buffer (NanoVDB's validator bounds the
// root table by the root's own claimed size and skips leaves, so this comes first). Nodes are
// handled through pointers until checked: binding a reference to a misaligned or outside
// address (as tree().root() and *iterator do) is already undefined behaviour.
template <typename T>
std::string check_layout(const nanovdb::NanoGrid<T>& grid, uint64_t buffer_size) {
  const uint8_t* lo = reinterpret_cast<const uint8_t*>(&grid);
  const uint8_t* hi = lo + buffer_size;
  const auto inside = [&](const void* p, size_t n) {
    const uint8_t* b = static_cast<const uint8_t*>(p);
    return b >= lo && b <= hi && size_t(hi - b) >= n &&
           (reinterpret_cast<uintptr_t>(b) % NANOVDB_DATA_ALIGNMENT) == 0;
  };
  if (!inside(&grid.tree(), sizeof(grid.tree()))) return "tree outside the buffer";
  const uint64_t tree_at = uint64_t(reinterpret_cast<const uint8_t*>(&grid.tree()) - lo);
  if (grid.tree().data()->mNodeOffset[3] > buffer_size - tree_at) return "root outside the buffer";
  using RootT = typename nanovdb::NanoGrid<T>::RootType;
  const RootT* root = grid.tree().data()->template getRoot<RootT>();
  if (!inside(root, sizeof(RootT)) || !inside(root, root->memUsage()) ||
      !child_offsets_inside(*root, lo, buffer_size))
    return "root outside the buffer";
  for (auto upper = root->beginChild(); upper; ++upper) {
    if (!inside(upper.operator->(), sizeof(*upper)) || !child_offsets_inside(*upper, lo, buffer_size))
      return "node outside the buffer";
    for (auto lower = upper->beginChild(); lower; ++lower) {
      if (!inside(lower.operator->(), sizeof(*lower)) || !child_offsets_inside(*lower, lo, buffer_size))
        return "node outside the buffer";
      for (auto leaf = lower->beginChild(); leaf; ++leaf)
        if (!inside(leaf.operator->(), sizeof(*leaf))) return "leaf outside the buffer";
    }
  }
  return nanovdb::GridValidator<T>::check(grid, /*detailed=*/true);
}

template <typename T>
void validate(const NanoGridHandle& handle, const std::string& name, const NvdbReader& reader) {
  const nanovdb::NanoGrid<T>* grid = handle.grid<T>();
  if (!grid) reader.fail("grid \"" + name + "\" has an unexpected type");
  const std::string problem = check_layout(*grid, handle.size());
  if (!problem.empty()) reader.fail("corrupt NanoVDB grid \"" + name + "\": " + problem);
}

}  // namespace

std::vector<GridEntry> list_nvdb_grids(const std::string& path, const SourceLocation& where) {
  NvdbReader reader(path, where);
  std::vector<GridEntry> entries;
  for (const NvdbRecord& r : reader.scan()) entries.push_back({r.name, type_name(r.meta.gridType)});
  return entries;
}

std::vector<NanoGridHandle> read_nvdb_grids(const std::string& path, const std::vector<GridRequest>& requests,
                                            const SourceLocation& where) {
  NvdbReader reader(path, where);
  const std::vector<NvdbRecord> records = reader.scan();
  std::vector<NanoGridHandle> handles;
  for (const GridRequest& request : requests) {
    const auto it = std::find_if(records.begin(), records.end(),
                                 [&](const NvdbRecord& r) { return r.name == request.name; });
    if (it == records.end()) reader.fail("has no grid named \"" + request.name + "\"");
    NanoGridHandle handle = reader.read_grid(*it);
    switch (request.kind) {
      case GridValueKind::kFloat:
        validate<float>(handle, request.name, reader);
        break;
      case GridValueKind::kVec3:
        validate<nanovdb::Vec3f>(handle, request.name, reader);
        break;
    }
    handles.push_back(std::move(handle));
  }
  return handles;
}

GridFileInfo describe_nvdb_file(const std::string& path) {
  NvdbReader reader(path, {});
  GridFileInfo info;
  info.format = "NanoVDB";
  for (const NvdbRecord& r : reader.scan()) {
    GridInfo g;
    g.name = r.name;
    g.type = type_name(r.meta.gridType);
    g.active_voxels = r.meta.voxelCount;
    g.active_leaves = r.meta.nodeCount[0];
    g.active_tiles = uint64_t(r.meta.tileCount[0]) + r.meta.tileCount[1] + r.meta.tileCount[2];
    g.memory_bytes = r.meta.gridSize;
    g.voxel_size = Vec3(float(r.meta.voxelSize[0]), float(r.meta.voxelSize[1]), float(r.meta.voxelSize[2]));
    if (r.meta.voxelCount > 0) {
      for (int a = 0; a < 3; ++a) {
        g.index_min[a] = r.meta.indexBBox.min()[a];
        g.index_max[a] = r.meta.indexBBox.max()[a];
      }
      // NanoVDB's world box spans voxel centres min..max + 1; OpenVDB's convention (and
      // ours) is the voxels' cells, min - 1/2..max + 1/2 (exact for axis-aligned maps).
      for (int a = 0; a < 3; ++a) {
        g.world_bounds.lo[a] = float(r.meta.worldBBox.min()[a] - 0.5 * r.meta.voxelSize[a]);
        g.world_bounds.hi[a] = float(r.meta.worldBBox.max()[a] - 0.5 * r.meta.voxelSize[a]);
      }
    }
    if (r.meta.gridType == nanovdb::GridType::Float) {
      // The value range is the root's statistics: read and validate the grid for it.
      const NanoGridHandle handle = reader.read_grid(r);
      validate<float>(handle, r.name, reader);
      const nanovdb::NanoGrid<float>* grid = handle.grid<float>();
      if (grid->hasMinMax() && r.meta.voxelCount > 0) {
        g.min_value = grid->tree().root().minimum();
        g.max_value = grid->tree().root().maximum();
      }
    }
    info.grids.push_back(std::move(g));
  }
  return info;
}

void write_nvdb_file(const std::string& path, const std::vector<SparseFloatGrid>& grids) {
  std::vector<NanoGridHandle> handles;
  for (const SparseFloatGrid& g : grids) handles.push_back(sparse_to_nanovdb(g, /*full_checksum=*/true));
  try {
    nanovdb::io::writeGrids<nanovdb::HostBuffer, std::vector>(path, handles, nanovdb::io::Codec::NONE);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(std::string("cannot write the NanoVDB file: ") + e.what());
  }
}

}  // namespace caligo
