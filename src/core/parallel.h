// The tile loop: an image is cut into square tiles that TBB hands to worker threads.
// Work inside a tile must depend only on the tile, never on the thread running it.
#pragma once

#include <functional>
#include <vector>

#include "core/vec.h"

namespace caligo {

struct Tile {
  int x0, y0, x1, y1;  // half-open pixel rectangle [x0, x1) x [y0, y1)
  int index;           // position in the tile list
};

std::vector<Tile> make_tiles(Vec2i resolution, int tile_size);

// Runs `body` once per tile on the current TBB arena; returns when all are done.
// Each render thread has flush-to-zero and denormals-are-zero set before running tiles.
void parallel_for_tiles(const std::vector<Tile>& tiles, const std::function<void(const Tile&)>& body);

// Runs `body(i)` for i in [0, n) in parallel.
void parallel_for(int n, const std::function<void(int)>& body);

// Sets MXCSR flush-to-zero and denormals-are-zero for the calling thread (Embree runs
// far slower on denormals).
void enable_flush_to_zero();

}  // namespace caligo
