// Procedural 3D noise that modulates a medium's density (the seed's "3D noise texture"):
// a tileable lattice of value noise, smoothed by trilinear interpolation of a smooth
// (quintic-faded) lattice, sampled in world space. The texture is built once, deterministically,
// and shared: the path tracer and the real-time passes read the same values.
#pragma once

#include <vector>

#include "core/vec.h"

namespace caligo {

// A periodic N^3 grid of values in [-1, 1]; lookup() interpolates with wrap-around
// addressing in lattice units, so lookup(p + N e_i) == lookup(p).
class NoiseTexture {
 public:
  static constexpr int kSize = 32;
  // The one texture every medium uses (built on first use, thread-safe).
  static const NoiseTexture& shared();

  float lookup(Vec3 lattice_position) const;
  const std::vector<float>& values() const { return values_; }  // kSize^3, x fastest

 private:
  NoiseTexture();
  std::vector<float> values_;
};

// density multiplier = max(0, 1 + amplitude * fbm(scale * (p - offset))) where fbm is two
// octaves of the texture (weights 2/3, 1/3) so it stays in [-1, 1]. `wind` (m/s) moves the
// pattern; SceneDesc::at_time sets offset = wind * time.
struct NoiseModulation {
  float scale = 1.0f;      // lattice cells per metre
  float amplitude = 0.5f;  // in [0, 1]: densities stay within [1 - a, 1 + a]
  Vec3 wind;
  Vec3 offset;
};

float noise_density(const NoiseModulation& noise, Vec3 world_position);
// Upper bound of noise_density (for majorants).
inline float noise_density_max(const NoiseModulation& noise) { return 1.0f + noise.amplitude; }

}  // namespace caligo
