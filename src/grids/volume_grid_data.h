// What a VolumeGrid holds: the NanoVDB grids (owned through their handles) and the block
// structure built over them at load. Includes NanoVDB; only grid code needs it.
#pragma once

#include <cstdint>

#include <nanovdb/NanoVDB.h>

#include "grids/grid_blocks.h"
#include "grids/volume_grid.h"
#include "grids/volume_grid_build.h"

namespace caligo {

struct VolumeGridData {
  NanoGrids handles;
  // Views into `handles` (never null for density; null where the set lacks the channel).
  const nanovdb::FloatGrid* density = nullptr;
  const nanovdb::FloatGrid* temperature = nullptr;
  const nanovdb::FloatGrid* flame = nullptr;
  const nanovdb::Vec3fGrid* color = nullptr;
  // Temperature and flame share the density grid's index space (checked at build); the colour
  // grid may not, in which case it is looked up through its own map and no block is flagged
  // constant (its colour, which tints sigma_s, may vary inside any block).
  bool color_shares_index_space = false;

  GridBlocks blocks;
  GridStatistics statistics;
  Bounds3 world_bounds;
  float voxel_size = 0.0f;
  // Distinguishes grids for per-thread accessor caches (an address may be reused after a grid
  // is freed; an id never is).
  uint64_t id = 0;
};

}  // namespace caligo
