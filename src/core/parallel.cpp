#include "core/parallel.h"

#include <pmmintrin.h>
#include <xmmintrin.h>

#include <algorithm>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace caligo {

std::vector<Tile> make_tiles(Vec2i resolution, int tile_size) {
  std::vector<Tile> tiles;
  for (int y = 0; y < resolution.y; y += tile_size)
    for (int x = 0; x < resolution.x; x += tile_size)
      tiles.push_back({x, y, std::min(x + tile_size, resolution.x), std::min(y + tile_size, resolution.y),
                       int(tiles.size())});
  return tiles;
}

void enable_flush_to_zero() {
  _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
  _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
}

void parallel_for_tiles(const std::vector<Tile>& tiles, const std::function<void(const Tile&)>& body) {
  tbb::parallel_for(tbb::blocked_range<size_t>(0, tiles.size(), 1), [&](const tbb::blocked_range<size_t>& r) {
    enable_flush_to_zero();
    for (size_t i = r.begin(); i != r.end(); ++i) body(tiles[i]);
  });
}

void parallel_for(int n, const std::function<void(int)>& body) {
  tbb::parallel_for(0, n, [&](int i) { body(i); });
}

}  // namespace caligo
