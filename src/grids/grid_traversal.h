// Ray traversal of the two-level block structure (grids/grid_blocks.h): a 3D DDA
// (Amanatides & Woo 1987) over the 64^3-voxel parents, empty parents costing one step each,
// then a DDA over the 8^3 blocks inside each occupied parent. Works in the grid's index space;
// an affine world-to-index map leaves the ray parameter t unchanged, so the caller's t holds.
#pragma once

#include <vector>

#include "core/vec.h"
#include "grids/grid_blocks.h"
#include "grids/volume_grid.h"

namespace caligo {

// Appends to `out`, in order along the ray x(t) = origin + t * direction (index space), the
// intervals of [t0, t1] that cross occupied blocks. Consecutive occupied blocks merge while
// max/min of their majorants, and of their minima (0 only with 0), stays within
// 1 + merge_tolerance (an interval's minimum is its blocks' least); constant blocks merge only with
// touching constant blocks (which hold the same values: see grid_blocks.h). Never merges with
// intervals already in `out`. Degenerate rays (zero or non-finite direction, NaN) yield nothing.
void block_intervals(const GridBlocks& blocks, Vec3 origin, Vec3 direction, float t0, float t1,
                     float merge_tolerance, std::vector<GridInterval>& out);

}  // namespace caligo
