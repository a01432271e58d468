// A volume's sparse grids (density, and optionally temperature, flame and a colour `Cd`),
// held in NanoVDB form, with a two-level block structure over them for empty-space and
// constant-block skipping (the seed's "two level structure to minimize marching through
// empty space"). Immutable once built and shared between threads; per-thread lookup state
// lives in a GridAccessorCache. This header includes no NanoVDB or OpenVDB header.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/bounds.h"
#include "core/ray.h"
#include "core/rgb.h"

namespace caligo {

enum class GridFilter { kTrilinear, kNearest };

// One stretch of a ray over occupied blocks, in the caller's ray parameter t.
struct GridInterval {
  float t0, t1;
  float density_max;  // bounds the (filtered) density grid everywhere on [t0, t1]
  bool constant;      // every channel's filtered value is the same everywhere on [t0, t1]
  float density_min = 0.0f;  // >= 0 and below the filtered density everywhere on [t0, t1]
};

// The grid set's values at one point (channels the set lacks read as 0, colour as 1).
struct GridValues {
  float density = 0.0f;
  float temperature = 0.0f;
  float flame = 0.0f;
  RGB color{1.0f};
};

struct GridStatistics {
  uint64_t active_voxels = 0;
  uint64_t blocks = 0;           // occupied 8^3 block regions (the filter footprint included: a voxel
                                 // on a block corner makes up to 8 of them)
  uint64_t constant_blocks = 0;  // of which every voxel is equal
  float min_value = 0.0f, max_value = 0.0f;  // of the density grid's active voxels
};

class GridAccessorCache;  // per-thread lookup state (grids/grid_accessor_cache.h)
struct GridBlocks;        // the block structure (grids/grid_blocks.h)
struct VolumeGridData;    // the NanoVDB grids and the block structure (grids/volume_grid_data.h)

class VolumeGrid {
 public:
  explicit VolumeGrid(std::unique_ptr<VolumeGridData> data);
  ~VolumeGrid();
  VolumeGrid(const VolumeGrid&) = delete;
  VolumeGrid& operator=(const VolumeGrid&) = delete;

  // World space here is the grids' own (their index-to-world maps); a scene placement is the caller's.
  Bounds3 world_bounds() const;  // where any channel may be non-zero, filter footprint included
  float voxel_size() const;      // smallest world-space voxel edge
  float max_density() const;
  bool has_temperature() const;
  bool has_flame() const;
  bool has_color() const;
  GridStatistics statistics() const;
  size_t memory_bytes() const;   // everything this object holds
  size_t nanovdb_bytes() const;  // the NanoVDB grids alone

  // Appends, in order along the ray, the intervals of [t0, t1] that cross occupied blocks
  // (a two-level DDA: parents, then 8^3 blocks). Consecutive blocks merge while their
  // majorants and their minima agree within `merge_tolerance` (relative); constant blocks merge only with
  // equal constant blocks. Empty space yields nothing.
  void intervals(const Ray& ray, float t0, float t1, std::vector<GridInterval>& out,
                 float merge_tolerance = 0.25f) const;

  // The block structure's index space (voxel centres at integer coordinates) and its affine map
  // to the grids' world space.
  const GridBlocks& blocks() const;
  Vec3 index_to_world(Vec3 index) const;
  Vec3 index_to_world_vector(Vec3 v) const;
  Vec3 world_to_index(Vec3 p) const;
  Vec3 world_to_index_vector(Vec3 v) const;

  float density(Vec3 p, GridFilter filter, GridAccessorCache& cache) const;
  GridValues values(Vec3 p, GridFilter filter, GridAccessorCache& cache) const;

  const VolumeGridData& data() const { return *data_; }

 private:
  std::unique_ptr<VolumeGridData> data_;
};

}  // namespace caligo
