// PCG32 (O'Neill 2014, "PCG: A family of simple fast space-efficient statistically good
// algorithms for random number generation"): 64-bit state, 32-bit output, selectable stream.
// Plus the integer hashes the sampler uses to derive independent seeds.
#pragma once

#include <cstdint>

#include "core/math.h"

namespace caligo {

class Pcg32 {
 public:
  Pcg32() { seed(0x853c49e6748fea9bULL, 0xda3e39cb94b95bdbULL); }
  Pcg32(uint64_t state, uint64_t stream) { seed(state, stream); }

  void seed(uint64_t state, uint64_t stream) {
    state_ = 0;
    inc_ = (stream << 1u) | 1u;
    next_u32();
    state_ += state;
    next_u32();
  }

  uint32_t next_u32() {
    const uint64_t old = state_;
    state_ = old * 6364136223846793005ULL + inc_;
    const uint32_t xorshifted = uint32_t(((old >> 18u) ^ old) >> 27u);
    const uint32_t rot = uint32_t(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31u));
  }

  // Uniform in [0, 1).
  float next_float() { return std::fmin(float(next_u32()) * 0x1p-32f, kOneMinusEpsilon); }

 private:
  uint64_t state_ = 0;
  uint64_t inc_ = 0;
};

// A 32-bit avalanche mix (Chris Wellons' "lowbias32"): fixed integer arithmetic, so noise
// built on it is identical on every platform and run.
inline uint32_t lowbias32(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

// 64-bit finaliser of MurmurHash3: a bijective avalanche mix.
inline uint64_t mix_bits(uint64_t v) {
  v ^= v >> 33;
  v *= 0xff51afd7ed558ccdULL;
  v ^= v >> 33;
  v *= 0xc4ceb9fe1a85ec53ULL;
  v ^= v >> 33;
  return v;
}

inline uint64_t hash_combine(uint64_t seed, uint64_t v) {
  return mix_bits(seed ^ (v + 0x9e3779b97f4a7c15ULL + (seed << 6) + (seed >> 2)));
}

template <typename... Ts>
uint64_t hash_values(uint64_t first, Ts... rest) {
  uint64_t h = mix_bits(first);
  ((h = hash_combine(h, uint64_t(rest))), ...);
  return h;
}

}  // namespace caligo
