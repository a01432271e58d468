// The render's tile loop (core/parallel.h, used by render.cpp): the tiles of any image
// cover every pixel exactly once, also when the tile size does not divide the resolution,
// and parallel_for_tiles runs each tile exactly once.
#include <gtest/gtest.h>

#include <atomic>
#include <vector>

#include "core/parallel.h"

namespace caligo {
namespace {

// How many tiles cover each pixel, with the tiles' own sanity checked on the way.
std::vector<int> coverage(const std::vector<Tile>& tiles, Vec2i resolution, int tile_size) {
  std::vector<int> count(size_t(resolution.x) * size_t(resolution.y), 0);
  for (size_t i = 0; i < tiles.size(); ++i) {
    const Tile& t = tiles[i];
    EXPECT_EQ(t.index, int(i));
    EXPECT_TRUE(0 <= t.x0 && t.x0 < t.x1 && t.x1 <= resolution.x) << t.x0 << ".." << t.x1;
    EXPECT_TRUE(0 <= t.y0 && t.y0 < t.y1 && t.y1 <= resolution.y) << t.y0 << ".." << t.y1;
    EXPECT_LE(t.x1 - t.x0, tile_size);
    EXPECT_LE(t.y1 - t.y0, tile_size);
    for (int y = t.y0; y < t.y1; ++y)
      for (int x = t.x0; x < t.x1; ++x) ++count[size_t(y) * size_t(resolution.x) + size_t(x)];
  }
  return count;
}

TEST(Tiles, CoverEveryPixelExactlyOnce) {
  const Vec2i resolutions[] = {{1, 1}, {16, 16}, {17, 16}, {33, 7}, {7, 33}, {100, 37}, {5, 5}, {64, 1}};
  for (const Vec2i res : resolutions)
    for (const int tile_size : {1, 3, 7, 16, 64}) {
      SCOPED_TRACE(::testing::Message() << res.x << "x" << res.y << " tiles of " << tile_size);
      const std::vector<Tile> tiles = make_tiles(res, tile_size);
      const auto per_axis = [&](int n) { return (n + tile_size - 1) / tile_size; };
      EXPECT_EQ(tiles.size(), size_t(per_axis(res.x)) * size_t(per_axis(res.y)));
      const std::vector<int> count = coverage(tiles, res, tile_size);
      for (size_t p = 0; p < count.size(); ++p) ASSERT_EQ(count[p], 1) << "pixel " << p;
    }
}

TEST(Tiles, AnEmptyImageHasNoTiles) {
  EXPECT_TRUE(make_tiles({0, 0}, 16).empty());
  EXPECT_TRUE(make_tiles({0, 8}, 16).empty());
  EXPECT_TRUE(make_tiles({8, 0}, 16).empty());
}

TEST(Tiles, ParallelLoopRunsEveryTileOnce) {
  const std::vector<Tile> tiles = make_tiles({101, 57}, 8);
  std::vector<std::atomic<int>> runs(tiles.size());
  std::atomic<long> pixels{0};
  parallel_for_tiles(tiles, [&](const Tile& t) {
    runs[size_t(t.index)].fetch_add(1);
    pixels.fetch_add(long(t.x1 - t.x0) * (t.y1 - t.y0));
  });
  for (size_t i = 0; i < runs.size(); ++i) EXPECT_EQ(runs[i].load(), 1) << "tile " << i;
  EXPECT_EQ(pixels.load(), 101L * 57L);
}

}  // namespace
}  // namespace caligo
