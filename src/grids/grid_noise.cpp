#include "grids/grid_noise.h"

#include <cmath>

#include "core/rng.h"

namespace caligo {
namespace {

// A 32-bit avalanche of the lattice point.
uint32_t hash_lattice(uint32_t seed, int i, int j, int k) {
  return lowbias32(seed ^ (uint32_t(i) * 0x8da6b343u) ^ (uint32_t(j) * 0xd8163841u) ^ (uint32_t(k) * 0xcb1ab31fu));
}

// Dot product of the offset with one of the 12 edge directions (Perlin 2002), picked by hash.
float gradient_dot(uint32_t h, float x, float y, float z) {
  switch (h % 12u) {
    case 0:
      return x + y;
    case 1:
      return -x + y;
    case 2:
      return x - y;
    case 3:
      return -x - y;
    case 4:
      return x + z;
    case 5:
      return -x + z;
    case 6:
      return x - z;
    case 7:
      return -x - z;
    case 8:
      return y + z;
    case 9:
      return -y + z;
    case 10:
      return y - z;
    default:
      return -y - z;
  }
}

float fade(float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); }
float mix(float a, float b, float t) { return a + t * (b - a); }

}  // namespace

GradientNoise::GradientNoise(uint64_t seed) : seed_(uint32_t(mix_bits(seed))) {}

float GradientNoise::operator()(Vec3 p) const {
  const float fx = std::floor(p.x), fy = std::floor(p.y), fz = std::floor(p.z);
  const int i = int(fx), j = int(fy), k = int(fz);
  const float x = p.x - fx, y = p.y - fy, z = p.z - fz;
  const float u = fade(x), v = fade(y), w = fade(z);
  const auto g = [&](int di, int dj, int dk) {
    return gradient_dot(hash_lattice(seed_, i + di, j + dj, k + dk), x - float(di), y - float(dj),
                        z - float(dk));
  };
  const float x00 = mix(g(0, 0, 0), g(1, 0, 0), u), x10 = mix(g(0, 1, 0), g(1, 1, 0), u);
  const float x01 = mix(g(0, 0, 1), g(1, 0, 1), u), x11 = mix(g(0, 1, 1), g(1, 1, 1), u);
  return mix(mix(x00, x10, v), mix(x01, x11, v), w);
}

float GradientNoise::fbm(Vec3 p, int octaves) const {
  float sum = 0.0f, amplitude = 1.0f, total = 0.0f;
  for (int o = 0; o < octaves; ++o) {
    // Each octave is shifted so that the lattice points of successive octaves do not line up.
    sum += amplitude * (*this)(p + Vec3(17.3f * float(o)));
    total += amplitude;
    p *= 2.0f;
    amplitude *= 0.5f;
  }
  return sum / total;
}

float GradientNoise::billow(Vec3 p, int octaves) const {
  float sum = 0.0f, amplitude = 1.0f, total = 0.0f;
  for (int o = 0; o < octaves; ++o) {
    sum += amplitude * (1.0f - std::min(1.0f, std::abs((*this)(p + Vec3(31.7f * float(o))))));
    total += amplitude;
    p *= 2.0f;
    amplitude *= 0.5f;
  }
  return sum / total;
}

}  // namespace caligo
