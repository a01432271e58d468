// Per-thread state of everything that asks volume primitives for intervals or coefficients:
// the interval list a ray's primitives append to, scratch for grid and mesh traversal, and
// the grid accessors (NanoVDB caches the tree path of its last lookup, so one thread
// reusing one accessor per grid turns most lookups into a leaf access). One per thread,
// reused from ray to ray: nothing here allocates once the vectors have grown.
#pragma once

#include <memory>
#include <utility>
#include <vector>

#include "geometry/embree_scene.h"
#include "grids/volume_grid.h"
#include "volumes/interval.h"

namespace caligo {

struct VolumeContext {
  VolumeContext();
  ~VolumeContext();
  VolumeContext(VolumeContext&&) noexcept;
  VolumeContext& operator=(VolumeContext&&) noexcept;

  std::vector<VolumeInterval> intervals;  // what VolumeScene::intervals() appends to
  std::vector<uint32_t> candidates;       // primitives whose bounds the ray crosses
  std::vector<GridInterval> grid_intervals;
  std::vector<SurfaceHit> mesh_hits;
  std::vector<RayRange> mesh_intervals;
  std::unique_ptr<GridAccessorCache> grids;

  // Grid traversal switches, on in rendering; benchmarks turn them off to measure what they save.
  bool skip_empty_blocks = true;       // off: a grid is one interval over its bounds
  bool constant_blocks_one_step = true;  // off: constant blocks are marched voxel by voxel
};

}  // namespace caligo
