#include "volumes/noise.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/math.h"
#include "core/rng.h"

namespace caligo {
namespace {

constexpr int kN = NoiseTexture::kSize;


// The quintic fade 6t^5 - 15t^4 + 10t^3 (Perlin 2002): C2 across lattice cells, so the
// density has no visible grid creases. fade(1 - t) = 1 - fade(t), which makes the mean of the
// interpolated field over a period equal the mean of the lattice values.
float fade(float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); }

int wrap(int i) { return i & (kN - 1); }
static_assert((kN & (kN - 1)) == 0, "wrap() needs a power-of-two size");

// Reduces a lattice coordinate to [0, kN) before splitting it, so large positions (wind
// over long animations) keep their precision and cannot overflow an int.
void split(float x, int& cell, float& t) {
  const float r = x - kN * std::floor(x / kN);
  const float f = std::floor(r);
  cell = wrap(static_cast<int>(f));
  t = std::clamp(r - f, 0.0f, 1.0f);
}

}  // namespace

const NoiseTexture& NoiseTexture::shared() {
  static const NoiseTexture texture;  // C++11 guarantees thread-safe one-time construction
  return texture;
}

// Hashed values, shifted to mean exactly 0 and scaled so the largest magnitude is 1: a
// density modulation then averages to 1 over a period and stays within [1 - a, 1 + a].
NoiseTexture::NoiseTexture() : values_(static_cast<size_t>(kN) * kN * kN) {
  for (size_t i = 0; i < values_.size(); ++i)
    values_[i] = static_cast<float>(lowbias32(static_cast<uint32_t>(i) ^ 0x9e3779b9u) >> 8) * 0x1p-24f;
  double sum = 0.0;
  for (float v : values_) sum += v;
  const float mean = static_cast<float>(sum / static_cast<double>(values_.size()));
  float largest = 0.0f;
  for (float& v : values_) {
    v -= mean;
    largest = std::max(largest, std::abs(v));
  }
  for (float& v : values_) v /= largest;
}

float NoiseTexture::lookup(Vec3 p) const {
  int c[3];
  float t[3];
  for (int a = 0; a < 3; ++a) {
    split(p[a], c[a], t[a]);
    t[a] = fade(t[a]);
  }
  auto at = [&](int dx, int dy, int dz) {
    return values_[(static_cast<size_t>(wrap(c[2] + dz)) * kN + wrap(c[1] + dy)) * kN + wrap(c[0] + dx)];
  };
  const float x00 = lerp(t[0], at(0, 0, 0), at(1, 0, 0));
  const float x10 = lerp(t[0], at(0, 1, 0), at(1, 1, 0));
  const float x01 = lerp(t[0], at(0, 0, 1), at(1, 0, 1));
  const float x11 = lerp(t[0], at(0, 1, 1), at(1, 1, 1));
  return lerp(t[2], lerp(t[1], x00, x10), lerp(t[1], x01, x11));
}

float noise_density(const NoiseModulation& noise, Vec3 world_position) {
  const NoiseTexture& texture = NoiseTexture::shared();
  const Vec3 q = (world_position - noise.offset) * noise.scale;
  // The second octave is shifted by a non-lattice offset so it does not line up with the first.
  const float fbm = (2.0f / 3.0f) * texture.lookup(q) +
                    (1.0f / 3.0f) * texture.lookup(q * 2.0f + Vec3(11.37f, 5.71f, 17.13f));
  return std::max(0.0f, 1.0f + noise.amplitude * fbm);
}

}  // namespace caligo
