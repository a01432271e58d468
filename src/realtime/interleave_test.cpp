#include "realtime/interleave.h"

#include <gtest/gtest.h>

#include <vector>

namespace caligo {
namespace {

// Every tile covers each of the tile_size^2 offsets exactly once, for every frame seed,
// including partial-size tiles' full pattern and non-power-of-two sizes.
TEST(Interleave, EachTileCoversEveryOffsetOnce) {
  for (int tile : {2, 3, 8}) {
    const int n = tile * tile;
    for (uint32_t seed : {0u, 1u, 77u}) {
      for (int ty = 0; ty < 5; ++ty) {
        for (int tx = 0; tx < 7; ++tx) {
          std::vector<int> seen(size_t(n), 0);
          for (int y = 0; y < tile; ++y) {
            for (int x = 0; x < tile; ++x) {
              const float o = interleaved_offset(tx * tile + x, ty * tile + y, tile, seed);
              const int slot = int(o * float(n));
              ASSERT_GE(slot, 0);
              ASSERT_LT(slot, n);
              EXPECT_FLOAT_EQ(o, (float(slot) + 0.5f) / float(n));
              ++seen[size_t(slot)];
            }
          }
          for (int s = 0; s < n; ++s) EXPECT_EQ(seen[size_t(s)], 1) << "tile " << tile << " slot " << s;
        }
      }
    }
  }
}

// The order changes between tiles and between frames (randomised, not the seed's fixed table).
TEST(Interleave, OrderDependsOnTileAndFrame) {
  auto pattern = [](int tx, int ty, uint32_t seed) {
    std::vector<float> p;
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x) p.push_back(interleaved_offset(tx * 8 + x, ty * 8 + y, 8, seed));
    return p;
  };
  EXPECT_NE(pattern(0, 0, 1), pattern(1, 0, 1));
  EXPECT_NE(pattern(0, 0, 1), pattern(0, 1, 1));
  EXPECT_NE(pattern(2, 3, 1), pattern(2, 3, 2));
  EXPECT_EQ(pattern(2, 3, 5), pattern(2, 3, 5));
}

TEST(Interleave, TileSizeOneIsTheMidpoint) { EXPECT_EQ(interleaved_offset(5, 9, 1, 123), 0.5f); }

TEST(Interleave, PermuteIsABijection) {
  for (uint32_t n : {1u, 5u, 64u, 100u}) {
    std::vector<int> seen(n, 0);
    for (uint32_t i = 0; i < n; ++i) ++seen[permute_index(i, n, 0xdeadbeef)];
    for (uint32_t i = 0; i < n; ++i) EXPECT_EQ(seen[i], 1);
  }
}

}  // namespace
}  // namespace caligo
