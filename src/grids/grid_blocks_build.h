// Building the two-level block structure (grids/grid_blocks.h) from NanoVDB grids.
#pragma once

#include <nanovdb/NanoVDB.h>

#include "core/error.h"
#include "grids/grid_blocks.h"

namespace caligo {

struct BlockChannels {
  const nanovdb::FloatGrid* density = nullptr;  // required
  const nanovdb::FloatGrid* temperature = nullptr;
  const nanovdb::FloatGrid* flame = nullptr;
  // Only when it shares the density grid's index space; it then takes part in constancy.
  const nanovdb::Vec3fGrid* color = nullptr;
};

// Limits that keep a hostile or absurd grid from allocating gigabytes: at most this many
// occupied 64^3-voxel parents, and a dense parent array no larger than
// max(kMinParentCells, kParentCellsPerOccupied x occupied parents).
inline constexpr int64_t kMaxOccupiedParents = int64_t(1) << 15;
inline constexpr int64_t kMinParentCells = int64_t(1) << 18;
inline constexpr int64_t kParentCellsPerOccupied = 64;

// All channels must share the density grid's index space (the caller checks). Throws
// InputError at `where` when the grid is too large or too sparse for the limits above.
GridBlocks build_grid_blocks(const BlockChannels& channels, const SourceLocation& where);

}  // namespace caligo
