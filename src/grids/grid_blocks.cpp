#include "grids/grid_blocks.h"

namespace caligo {

const ParentCell* GridBlocks::parent(int32_t px, int32_t py, int32_t pz) const {
  const int64_t x = int64_t(px) - parent_lo[0], y = int64_t(py) - parent_lo[1],
                z = int64_t(pz) - parent_lo[2];
  if (x < 0 || y < 0 || z < 0 || x >= parent_dims[0] || y >= parent_dims[1] || z >= parent_dims[2])
    return nullptr;
  const int32_t index = parent_index[slot(x, y, z)];
  return index < 0 ? nullptr : &parents[size_t(index)];
}

BlockRecord GridBlocks::block(int32_t bx, int32_t by, int32_t bz) const {
  const ParentCell* cell =
      parent(floor_div(bx, kParentBlocks), floor_div(by, kParentBlocks), floor_div(bz, kParentBlocks));
  if (!cell) return {};
  const int i = ParentCell::local_index(bx, by, bz);
  if (!cell->occupied(i)) return {};
  return {true, cell->constant(i), cell->majorant[i], cell->minimum[i], TightBox::unpack(cell->tight_box[i])};
}

}  // namespace caligo
