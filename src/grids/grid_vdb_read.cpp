// OpenVDB files in: listing, reading (with conversion to NanoVDB) and description. OpenVDB
// throws its own exception types, and std ones for allocation failures: every one becomes an
// InputError naming the file. Delayed loading is off: it memory-maps the file, and a
// truncated file then faults (SIGBUS) long after the read "succeeded".
#include <openvdb/io/File.h>
#include <openvdb/io/Stream.h>
#include <openvdb/tools/ValueTransformer.h>

#include <nanovdb/util/OpenToNanoVDB.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <set>
#include <tuple>
#include <type_traits>

#include "grids/crash_probe.h"
#include "grids/grid_io_internal.h"
#include "grids/openvdb_bridge.h"

namespace caligo {
namespace {

// Far beyond any grid a render needs (a 1600^3 dense block); stops a file whose root tiles
// claim 4096^3 voxels from reaching the block structure.
constexpr uint64_t kMaxActiveVoxels = uint64_t(1) << 32;

// Runs `body`, turning whatever OpenVDB or the allocator throws into a located InputError.
template <typename Body>
auto guarded(const std::string& path, const SourceLocation& where, Body body) -> decltype(body()) {
  try {
    return body();
  } catch (const InputError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw_grid_file_error(path, where,
                          "cannot read the OpenVDB file: it asks for more memory than is available");
  } catch (const std::exception& e) {
    throw_grid_file_error(path, where,
                          std::string("cannot read the OpenVDB file (corrupt or truncated?): ") + e.what());
  } catch (...) {
    throw_grid_file_error(path, where, "cannot read the OpenVDB file (corrupt or truncated?)");
  }
}

// OpenVDB has no checksums and corrupts memory on some corrupt files (see crash_probe.h), so
// a file is first read whole in a throw-away child process, once per version of the file
// (path, size, modification time); a crash or exception there is a located error here. The
// child may use 1 GiB plus 256 times the file's size (more than any compression ratio
// OpenVDB reaches), so corrupt lengths that ask for gigabytes fail fast.
void probe_vdb_file(const std::string& path, const SourceLocation& where, bool has_offsets) {
  static std::mutex mutex;
  static std::set<std::tuple<std::string, uintmax_t, int64_t>> verified;
  std::error_code ec;
  const uintmax_t size = std::filesystem::file_size(path, ec);
  const int64_t mtime = std::filesystem::last_write_time(path, ec).time_since_epoch().count();
  const auto key = std::make_tuple(path, size, mtime);
  {
    const std::lock_guard lock(mutex);
    if (verified.count(key)) return;
  }
  const auto timeout = std::chrono::milliseconds(30000 + 50 * int64_t(size >> 20));
  const ProbeOutcome outcome = probe_in_child(
      [&] {
        // Kept alive: the child exits without destructors (freeing a tree runs TBB).
        static openvdb::GridPtrVecPtr grids;
        openvdb::io::File file(path);
        file.open(/*delayLoad=*/false);
        grids = file.getGrids();
        if (has_offsets) return;
        // A file written as a stream has no offsets that say where it should end, and OpenVDB
        // can read one cut short without complaint (the missing bytes are whatever memory
        // held). Read again through a stream watched here: a read past the end leaves it failed.
        std::ifstream in(path, std::ios::binary);
        openvdb::io::Stream stream(in);
        grids = stream.getGrids();
        if (!in) throw std::runtime_error("truncated: the grids end past the end of the file");
      },
      timeout, (uint64_t(1) << 30) + 256 * uint64_t(size));
  switch (outcome.result) {
    case ProbeResult::kSurvived:
      break;
    case ProbeResult::kUnknown:  // no verdict (fork failed, or timed out): read as usual
      return;
    case ProbeResult::kThrew:  // never retried here: the failed read may have overrun a buffer
      throw_grid_file_error(path, where,
                            "cannot read the OpenVDB file (corrupt or truncated?): " + outcome.message);
    case ProbeResult::kCrashed:
      throw_grid_file_error(path, where, "corrupt OpenVDB file (reading it crashes OpenVDB)");
  }
  const std::lock_guard lock(mutex);
  verified.insert(key);
}

struct OpenFile {
  OpenFile(const std::string& path, const SourceLocation& where) : file(path) {
    probe_vdb_file(path, where, check_vdb_layout(path, where));
    file.open(/*delayLoad=*/false);
  }
  ~OpenFile() {
    if (file.isOpen()) file.close();
  }
  openvdb::io::File file;
};

template <typename To, typename From>
typename To::Ptr convert_grid(const From& from) {
  // Tree's converting constructor casts every value, tile and leaf (double -> float).
  auto tree = std::make_shared<typename To::TreeType>(from.tree());
  typename To::Ptr to = To::create(tree);
  to->setTransform(from.transform().copy());
  to->setName(from.getName());
  to->setGridClass(from.getGridClass());
  return to;
}

NanoGridHandle read_one(openvdb::io::File& file, const GridRequest& request, const std::string& path,
                        const SourceLocation& where) {
  const openvdb::GridBase::Ptr base = file.readGrid(request.name);
  if (!base) throw_grid_file_error(path, where, "has no grid named \"" + request.name + "\"");
  if (!base->transform().isLinear())
    throw_grid_file_error(path, where, "grid \"" + request.name + "\" has a non-linear (frustum) transform");
  if (base->activeVoxelCount() > kMaxActiveVoxels)
    throw_grid_file_error(path, where,
                          "grid \"" + request.name + "\" has " + std::to_string(base->activeVoxelCount()) +
                              " active voxels (more than 2^32)");
  const std::string wrong = "grid \"" + request.name + "\" holds " + base->valueType() + " values; expected ";
  switch (request.kind) {
    case GridValueKind::kFloat:
      if (auto g = openvdb::gridPtrCast<openvdb::FloatGrid>(base)) return to_nanovdb(*g, false);
      if (auto g = openvdb::gridPtrCast<openvdb::DoubleGrid>(base))
        return to_nanovdb(*convert_grid<openvdb::FloatGrid>(*g), false);
      throw_grid_file_error(path, where, wrong + "a float grid");
    case GridValueKind::kVec3:
      if (auto g = openvdb::gridPtrCast<openvdb::Vec3SGrid>(base)) return to_nanovdb(*g, false);
      if (auto g = openvdb::gridPtrCast<openvdb::Vec3DGrid>(base))
        return to_nanovdb(*convert_grid<openvdb::Vec3SGrid>(*g), false);
      throw_grid_file_error(path, where, wrong + "a vec3s grid");
  }
  throw_grid_file_error(path, where, "unknown grid kind");
}

// Min and max of a grid's active values (vectors: their length).
struct RangeOp {
  std::optional<double> lo, hi;
  template <typename GridT>
  void operator()(const GridT& grid) {
    using ValueT = typename GridT::ValueType;
    for (auto it = grid.cbeginValueOn(); it; ++it) {
      double v;
      if constexpr (openvdb::VecTraits<ValueT>::IsVec)
        v = double(it.getValue().length());
      else
        v = double(it.getValue());
      lo = lo ? std::min(*lo, v) : v;
      hi = hi ? std::max(*hi, v) : v;
    }
  }
};

GridInfo describe_grid(const openvdb::GridBase& grid) {
  GridInfo info;
  info.name = grid.getName();
  info.type = grid.valueType();
  info.active_voxels = grid.activeVoxelCount();
  info.active_leaves = grid.baseTree().leafCount();
  info.active_tiles = grid.baseTree().activeTileCount();
  info.memory_bytes = grid.memUsage();
  const openvdb::Vec3d vs = grid.transform().voxelSize();
  info.voxel_size = Vec3(float(vs.x()), float(vs.y()), float(vs.z()));
  const openvdb::CoordBBox box = grid.evalActiveVoxelBoundingBox();
  if (!box.empty()) {
    for (int a = 0; a < 3; ++a) {
      info.index_min[a] = box.min()[a];
      info.index_max[a] = box.max()[a];
    }
    for (int corner = 0; corner < 8; ++corner) {
      const openvdb::Vec3d p((corner & 1 ? box.max().x() + 0.5 : box.min().x() - 0.5),
                             (corner & 2 ? box.max().y() + 0.5 : box.min().y() - 0.5),
                             (corner & 4 ? box.max().z() + 0.5 : box.min().z() - 0.5));
      const openvdb::Vec3d w = grid.transform().indexToWorld(p);
      info.world_bounds.extend(Vec3(float(w.x()), float(w.y()), float(w.z())));
    }
  }
  RangeOp range;
  using Ranged = openvdb::NumericGridTypes::Append<openvdb::Vec3GridTypes>;
  if (grid.apply<Ranged>(range)) {
    info.min_value = range.lo;
    info.max_value = range.hi;
  }
  return info;
}

}  // namespace

void initialize_openvdb() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

NanoGridHandle to_nanovdb(const openvdb::FloatGrid& grid, bool full_checksum) {
  return nanovdb::openToNanoVDB(grid, nanovdb::StatsMode::MinMax,
                                full_checksum ? nanovdb::ChecksumMode::Full : nanovdb::ChecksumMode::Partial);
}

NanoGridHandle to_nanovdb(const openvdb::Vec3SGrid& grid, bool full_checksum) {
  return nanovdb::openToNanoVDB(grid, nanovdb::StatsMode::MinMax,
                                full_checksum ? nanovdb::ChecksumMode::Full : nanovdb::ChecksumMode::Partial);
}

std::vector<GridEntry> list_vdb_grids(const std::string& path, const SourceLocation& where) {
  initialize_openvdb();
  return guarded(path, where, [&] {
    OpenFile f(path, where);
    std::vector<GridEntry> entries;
    // Held by name: a range-for over *temporary_ptr would destroy the vector before the loop.
    const openvdb::GridPtrVecPtr grids = f.file.readAllGridMetadata();
    for (const openvdb::GridBase::Ptr& g : *grids) entries.push_back({g->getName(), g->valueType()});
    return entries;
  });
}

std::vector<NanoGridHandle> read_vdb_grids(const std::string& path, const std::vector<GridRequest>& requests,
                                           const SourceLocation& where) {
  initialize_openvdb();
  return guarded(path, where, [&] {
    OpenFile f(path, where);
    std::vector<NanoGridHandle> handles;
    for (const GridRequest& r : requests) handles.push_back(read_one(f.file, r, path, where));
    return handles;
  });
}

GridFileInfo describe_vdb_file(const std::string& path) {
  initialize_openvdb();
  return guarded(path, {}, [&] {
    OpenFile f(path, {});
    GridFileInfo info;
    info.format = "OpenVDB";
    const openvdb::GridPtrVecPtr grids = f.file.getGrids();
    for (const openvdb::GridBase::Ptr& g : *grids) info.grids.push_back(describe_grid(*g));
    return info;
  });
}

}  // namespace caligo
