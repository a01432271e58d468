// A float grid as a list of 8^3 blocks: the neutral form between the procedural generator,
// dense input and the file writers (no OpenVDB or NanoVDB type appears here). Blocks are the
// leaves OpenVDB and NanoVDB use, with their voxel order, so conversion copies 512 values at a
// time.
//
// Index space follows OpenVDB: voxel (i, j, k) has its centre at world
// origin + voxel_size * (i, j, k). A voxel is active exactly when its value is non-zero; the
// background (everything outside the blocks) is 0.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/vec.h"

namespace caligo {

inline constexpr int kBlockDim = 8;
inline constexpr int kBlockVoxels = kBlockDim * kBlockDim * kBlockDim;

// Offset of voxel (x, y, z) (each in [0, 8)) inside a block: x slowest, z fastest, as in
// OpenVDB's LeafNode::coordToOffset and NanoVDB's LeafNode::CoordToOffset.
constexpr int block_offset(int x, int y, int z) { return (x << 6) | (y << 3) | z; }

struct SparseBlock {
  std::array<int, 3> origin;  // index of the block's first voxel; each a multiple of 8
  std::array<float, kBlockVoxels> values;
};

struct SparseFloatGrid {
  std::string name;
  float voxel_size = 1.0f;          // metres
  Vec3 origin;                      // world position of the centre of voxel (0, 0, 0)
  std::vector<SparseBlock> blocks;  // distinct origins, none all-zero

  uint64_t active_voxels() const {
    uint64_t n = 0;
    for (const SparseBlock& b : blocks)
      for (float v : b.values) n += v != 0.0f;
    return n;
  }
};

}  // namespace caligo
