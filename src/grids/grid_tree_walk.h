// Visits every leaf and every tile (active or not) of a NanoVDB tree with origins derived from
// the root's tile keys. NanoVDB 32.4's own tile iterators are broken (InternalNode's
// ValueIterator does not compile; RootNode's getOrigin returns nothing), and node origin()s are
// derived from active-value bounding boxes, which are meaningless for nodes without active
// values; a walk from the root gives every node's true origin.
#pragma once

#include <cstdint>

#include <nanovdb/NanoVDB.h>

namespace caligo {

// leaf(const LeafT& leaf, Coord origin); tile(ValueT value, bool active, Coord origin, uint32_t dim)
// where dim is the tile's edge in voxels (8, 128 or 4096).
template <class GridT, class LeafF, class TileF>
void walk_tree(const GridT& grid, LeafF&& leaf, TileF&& tile) {
  const auto* root = grid.tree().root().data();
  auto walk_node = [&](const auto& self, const auto* node, nanovdb::Coord origin) -> void {
    using NodeT = std::remove_cv_t<std::remove_pointer_t<decltype(node)>>;
    using ChildT = typename NodeT::ChildNodeType;
    constexpr uint32_t kLog2 = NodeT::LOG2DIM, kChildTotal = ChildT::TOTAL;
    for (uint32_t n = 0; n < NodeT::SIZE; ++n) {
      const nanovdb::Coord at = origin.offsetBy(int32_t((n >> (2 * kLog2)) << kChildTotal),
                                                int32_t(((n >> kLog2) & ((1u << kLog2) - 1)) << kChildTotal),
                                                int32_t((n & ((1u << kLog2) - 1)) << kChildTotal));
      if (node->childMask().isOn(n)) {
        const ChildT* child = node->data()->getChild(n);
        if constexpr (ChildT::LEVEL == 0) {
          leaf(*child, at);
        } else {
          self(self, child, at);
        }
      } else {
        tile(node->data()->mTable[n].value, node->valueMask().isOn(n), at, ChildT::DIM);
      }
    }
  };
  for (uint32_t i = 0; i < root->mTableSize; ++i) {
    const auto* t = root->tile(i);
    if (t->isChild()) {
      walk_node(walk_node, root->getChild(t), t->origin());
    } else {
      tile(t->value, t->state != 0, t->origin(), uint32_t(1) << 12);
    }
  }
}

}  // namespace caligo
