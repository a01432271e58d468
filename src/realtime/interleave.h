// Interleaved sampling (Glatzel 2014, after Keller & Heidrich 2001): each pixel of a
// tile_size x tile_size tile starts its march at a different fraction of a step, so a
// tile together covers tile_size^2 offsets of the ray and the gather pass blurs them into
// one well-sampled ray. The seed randomises the indices once on the CPU; we draw a fresh
// permutation per tile and per frame (a keyed hash permutation, Kensler 2013, "Correlated
// Multi-Jittered Sampling"), so the pattern neither repeats across tiles nor stands still.
#pragma once

#include <cstdint>

namespace caligo {

// A bijection of [0, n) keyed by `key` (Kensler's permute with cycle walking).
uint32_t permute_index(uint32_t i, uint32_t n, uint32_t key);

// March offset in (0, 1) of a step for pixel (x, y): (perm(index in tile) + 0.5) / tile_size^2,
// the permutation keyed by the tile and the frame seed. tile_size 1 gives 0.5 (midpoints).
float interleaved_offset(int x, int y, int tile_size, uint32_t frame_seed);

// The same in two steps, for loops over a row: the key of the tile holding (x, y) (one hash,
// shared by the tile's pixels) and the offset of pixel (x, y) given that key.
uint32_t interleave_tile_key(int x, int y, int tile_size, uint32_t frame_seed);
float interleaved_offset_keyed(int x, int y, int tile_size, uint32_t tile_key);

}  // namespace caligo
