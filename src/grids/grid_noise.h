// Seeded 3D gradient noise for the procedural grids: Perlin's improved noise (quintic fade,
// gradients along the 12 cube-edge directions; Perlin 2002, "Improving Noise"), except that
// each lattice point's gradient comes from an integer hash of (seed, i, j, k) instead of a
// permutation table, so every 64-bit seed gives an unrelated, non-repeating field.
// Values lie in about [-1, 1] (|noise| <= 1.04). Immutable; safe to share between threads.
#pragma once

#include <cstdint>

#include "core/vec.h"

namespace caligo {

class GradientNoise {
 public:
  explicit GradientNoise(uint64_t seed);

  float operator()(Vec3 p) const;
  // Sum of `octaves` octaves (frequency x2, amplitude x0.5 each), divided by the sum of the
  // amplitudes so that it stays in about [-1, 1].
  float fbm(Vec3 p, int octaves) const;
  // "Billow" octaves 1 - |noise|, normalised to [0, 1]: rounded lobes with sharp creases, the
  // cauliflower look of cumulus.
  float billow(Vec3 p, int octaves) const;

 private:
  uint32_t seed_;
};

}  // namespace caligo
