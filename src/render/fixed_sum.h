// Exact, order-independent sums of float samples: each sample is rounded once to a multiple of
// 2^-50 and added as a 128-bit integer. Integer addition is associative, so a pixel's sum is
// the same bit for bit however its samples are split -- over tiles, checkpoints, resumed runs or
// MPI ranks -- and in whatever order the parts are merged. Floating-point sums are not: (a + b)
// + c and a + (b + c) differ in the last bits.
// Resolution 2^-50 (8.9e-16) is far below any radiance a render resolves; a sample of magnitude
// above 2^50 (1.1e15) saturates there (which only a broken scene produces), so no pixel sum can
// overflow before 2^26 such samples. 16 bytes per channel
// per pixel, twice a double: the price of exact merging (Film keeps only the chosen AOVs).
#pragma once

#include <cmath>
#include <cstdint>

namespace caligo {

class FixedSum {
 public:
  static constexpr double kScale = 0x1p50;

  // `x` must be finite (Film drops non-finite samples before they get here).
  void add(float x) { value_ += to_fixed(x); }
  void add(const FixedSum& other) { value_ += other.value_; }
  double value() const { return double(value_) / kScale; }
  // The raw integer, for saving and loading films.
  __int128 raw() const { return value_; }
  static FixedSum from_raw(__int128 raw) {
    FixedSum s;
    s.value_ = raw;
    return s;
  }
  friend bool operator==(const FixedSum&, const FixedSum&) = default;

 private:
  static __int128 to_fixed(float x) {
    const double scaled = double(x) * kScale;  // exact: a power-of-two scale of a float
    // The common case converts through a 64-bit integer (one instruction); rounding to nearest
    // is deterministic, so equal inputs give equal sums everywhere.
    if (std::fabs(scaled) < 0x1p62) return __int128(std::llrint(scaled));
    constexpr double kLimit = 0x1p100;
    if (!(std::fabs(scaled) < kLimit)) return scaled > 0.0 ? __int128(kLimit) : -__int128(kLimit);
    return __int128(scaled);  // an integer already (|scaled| >= 2^62 > 2^53)
  }

  __int128 value_ = 0;
};

}  // namespace caligo
