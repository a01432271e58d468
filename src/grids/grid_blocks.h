// The two-level block structure over a grid set (the seed's "two level structure to minimize
// marching through empty space"): level 1 is 8^3-voxel blocks (NanoVDB leaves), level 2 their
// parents of 8^3 blocks (64^3 voxels). Parents are a dense array over the occupied bounding
// box; each occupied parent owns a dense 8^3 array of block records.
//
// Index-space convention (voxel centres at integer coordinates): block b covers the region
// [8b, 8b + 8) on each axis. Trilinear and nearest lookups at any point of that region read only
// voxels 8b .. 8b + 8 inclusive (the block's own 8^3 voxels plus the first voxel layer of its
// +x/+y/+z neighbours): that closed 9^3 set is the block's *footprint*. A block's record is
// computed over its footprint, so
//   - majorant >= every filtered density at any point of the region (a convex combination of
//     footprint voxels), including the background where the footprint leaves the tree, and
//     minimum <= every one (clamped at 0): the control density of residual ratio tracking;
//   - constant means every channel's footprint voxels are equal, so the filtered value of every
//     channel is exactly constant over the region;
//   - occupied means some footprint voxel of density, temperature or flame is non-zero;
//   - the *tight box* bounds the part of the region where any of those channels' filtered
//     values can be non-zero: if the non-zero footprint voxels span offsets [a_lo, a_hi] from the
//     block origin on an axis (0..8), a trilinear lookup at x reads voxels floor(x) and
//     floor(x) + 1, so it is non-zero only on (a_lo - 1, a_hi + 1) (nearest reads a subset),
//     clamped to the region: [max(0, a_lo - 1), min(8, a_hi + 1)). It lets the traversal skip the
//     empty part of the "shell" of blocks around data, which the footprint makes occupied
//     although only their last voxel layer can be non-zero. Constant blocks have the full box.
// A consequence used by the traversal: two blocks whose regions touch (face, edge or corner)
// have overlapping footprints, so two touching constant blocks hold the same values.
// Immutable after build; thread-safe to read.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace caligo {

inline constexpr int kBlockEdge = 8;     // voxels per block edge (a NanoVDB leaf)
inline constexpr int kParentBlocks = 8;  // blocks per parent edge
inline constexpr int kParentVoxels = kBlockEdge * kParentBlocks;

// A block's tight box in voxel offsets from the block origin: [lo[a], hi[a]) with
// 0 <= lo < hi <= 8. Packed into 18 bits (3 per bound: lo, hi - 1), x fastest, so a parent's
// boxes cost 2 KiB rather than 3.
struct TightBox {
  std::array<uint8_t, 3> lo{0, 0, 0}, hi{kBlockEdge, kBlockEdge, kBlockEdge};

  bool full() const { return pack() == TightBox{}.pack(); }
  uint32_t pack() const {
    uint32_t p = 0;
    for (int a = 0; a < 3; ++a) p |= uint32_t(lo[a]) << (3 * a) | uint32_t(hi[a] - 1) << (9 + 3 * a);
    return p;
  }
  static TightBox unpack(uint32_t p) {
    TightBox b;
    for (int a = 0; a < 3; ++a) {
      b.lo[a] = uint8_t((p >> (3 * a)) & 7u);
      b.hi[a] = uint8_t(((p >> (9 + 3 * a)) & 7u) + 1);
    }
    return b;
  }
};
inline constexpr uint32_t kFullTightBox = 0777u << 9;  // lo = 0, hi - 1 = 7 on every axis

struct BlockRecord {
  bool occupied = false;
  bool constant = false;
  float majorant = 0.0f;  // of the filtered density over the block's region; 0 when empty
  float minimum = 0.0f;   // of the same, clamped at 0; 0 when empty
  TightBox box;           // the full region when empty or constant
};

// The 512 block records of one occupied parent. A negative majorant marks an empty block.
struct ParentCell {
  std::array<float, 512> majorant;
  std::array<float, 512> minimum;  // footprint minimum of the density, clamped at 0
  std::array<uint64_t, 8> constant_bits;
  std::array<uint32_t, 512> tight_box;  // TightBox::pack(); kFullTightBox for empty blocks

  static int local_index(int bx, int by, int bz) { return (bx & 7) | ((by & 7) << 3) | ((bz & 7) << 6); }
  bool occupied(int i) const { return majorant[i] >= 0.0f; }
  bool constant(int i) const { return (constant_bits[i >> 6] >> (i & 63)) & 1u; }
};

struct GridBlocks {
  // Occupied blocks' bounding box in block coordinates, inclusive; empty when lo > hi.
  std::array<int32_t, 3> block_lo{0, 0, 0}, block_hi{-1, -1, -1};
  // The dense parent array: parent p (in parent coordinates) is at index
  // (p - parent_lo) flattened x-fastest; entries are indices into `parents` or -1.
  std::array<int32_t, 3> parent_lo{0, 0, 0}, parent_dims{0, 0, 0};
  std::vector<int32_t> parent_index;
  std::vector<ParentCell> parents;

  uint64_t occupied_blocks = 0;
  uint64_t constant_blocks = 0;
  float max_majorant = 0.0f;

  bool empty() const { return occupied_blocks == 0; }
  size_t memory_bytes() const {
    return sizeof(GridBlocks) + parent_index.capacity() * sizeof(int32_t) +
           parents.capacity() * sizeof(ParentCell);
  }
  // The slot of parent_index for parent coordinates relative to parent_lo (each in
  // [0, parent_dims)): the one place the dense parent array's layout is written.
  size_t slot(int64_t x, int64_t y, int64_t z) const {
    return size_t(x + int64_t(parent_dims[0]) * (y + int64_t(parent_dims[1]) * z));
  }
  // The parent cell at parent coordinates (px, py, pz), or nullptr when it is empty or outside.
  const ParentCell* parent(int32_t px, int32_t py, int32_t pz) const;
  // The record of block (bx, by, bz) in block coordinates (an empty record outside).
  BlockRecord block(int32_t bx, int32_t by, int32_t bz) const;
};

// Calls visit(b, cell, i) for every occupied block, with b its block coordinates (int32_t[3]),
// cell its parent's records and i its index there, parent by parent in array order.
template <class Visit>
void for_each_occupied_block(const GridBlocks& blocks, Visit&& visit) {
  for (int64_t z = 0; z < blocks.parent_dims[2]; ++z)
    for (int64_t y = 0; y < blocks.parent_dims[1]; ++y)
      for (int64_t x = 0; x < blocks.parent_dims[0]; ++x) {
        const int32_t index = blocks.parent_index[blocks.slot(x, y, z)];
        if (index < 0) continue;
        const ParentCell& cell = blocks.parents[size_t(index)];
        for (int i = 0; i < 512; ++i) {
          if (!cell.occupied(i)) continue;
          const int32_t b[3] = {int32_t((blocks.parent_lo[0] + x) * kParentBlocks + (i & 7)),
                                int32_t((blocks.parent_lo[1] + y) * kParentBlocks + ((i >> 3) & 7)),
                                int32_t((blocks.parent_lo[2] + z) * kParentBlocks + (i >> 6))};
          visit(b, cell, i);
        }
      }
}

// Floor division by a power of two that is also right for negative coordinates.
inline int32_t floor_div(int32_t v, int32_t d) { return v >= 0 ? v / d : -((-v + d - 1) / d); }

}  // namespace caligo
