#include "realtime/interleave.h"

#include "core/rng.h"

namespace caligo {

uint32_t permute_index(uint32_t i, uint32_t n, uint32_t key) {
  uint32_t w = n - 1;
  w |= w >> 1;
  w |= w >> 2;
  w |= w >> 4;
  w |= w >> 8;
  w |= w >> 16;
  // Every step is a bijection of [0, w] (xor, odd multiply, xorshift under the mask), so
  // walking the cycle until the value falls below n gives a bijection of [0, n).
  do {
    i ^= key;
    i *= 0xe170893du;
    i ^= key >> 16;
    i ^= (i & w) >> 4;
    i ^= key >> 8;
    i *= 0x0929eb3fu;
    i ^= key >> 23;
    i ^= (i & w) >> 1;
    i *= 1u | key >> 27;
    i *= 0x6935fa69u;
    i ^= (i & w) >> 11;
    i *= 0x74dcb303u;
    i ^= (i & w) >> 2;
    i *= 0x9e501cc3u;
    i ^= (i & w) >> 2;
    i *= 0xc860a3dfu;
    i &= w;
    i ^= i >> 5;
  } while (i >= n);
  return (i + key) % n;
}

uint32_t interleave_tile_key(int x, int y, int tile_size, uint32_t frame_seed) {
  if (tile_size <= 1) return 0;
  return uint32_t(hash_values(uint64_t(x / tile_size), uint64_t(y / tile_size), frame_seed));
}

float interleaved_offset_keyed(int x, int y, int tile_size, uint32_t tile_key) {
  if (tile_size <= 1) return 0.5f;
  const uint32_t n = uint32_t(tile_size * tile_size);
  const uint32_t index = uint32_t((y % tile_size) * tile_size + (x % tile_size));
  return (float(permute_index(index, n, tile_key)) + 0.5f) / float(n);
}

float interleaved_offset(int x, int y, int tile_size, uint32_t frame_seed) {
  return interleaved_offset_keyed(x, y, tile_size, interleave_tile_key(x, y, tile_size, frame_seed));
}

}  // namespace caligo
