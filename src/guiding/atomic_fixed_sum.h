// An exact, order-independent sum of non-negative doubles that many threads add to at once:
// each value is rounded once to a multiple of 2^-32 and added as a 128-bit integer kept in two
// 64-bit atomics (a carry out of the low word goes to the high one). Integer addition is
// associative, so the total is the same bit for bit whichever thread added what in which order
// -- which is what makes a guiding field trained by any number of threads, in passes cut
// anywhere, or on several MPI ranks, the same field (guiding_field.h).
// Resolution 2^-32 (2.3e-10) is below any training value that matters (values are radiance over
// a pdf); values above 2^68 (3e20) saturate there.
#pragma once

#include <atomic>
#include <cmath>
#include <cstdint>

namespace caligo {

// The raw 128-bit total as two words, for saving, loading and summing across processes.
struct FixedTotal {
  uint64_t lo = 0, hi = 0;
  double value() const { return (double(hi) * 0x1p64 + double(lo)) * 0x1p-32; }
  FixedTotal& operator+=(FixedTotal o) {
    const uint64_t before = lo;
    lo += o.lo;
    hi += o.hi + (lo < before ? 1u : 0u);
    return *this;
  }
  friend bool operator==(FixedTotal, FixedTotal) = default;
};

class AtomicFixedSum {
 public:
  AtomicFixedSum() = default;
  AtomicFixedSum(const AtomicFixedSum& o) { set(o.total()); }
  AtomicFixedSum& operator=(const AtomicFixedSum& o) {
    set(o.total());
    return *this;
  }

  // Values that are not positive and finite add nothing.
  void add(double v) {
    if (!(v > 0.0)) return;
    const FixedTotal f = to_fixed(v);
    const uint64_t before = lo_.fetch_add(f.lo, std::memory_order_relaxed);
    const uint64_t carry = before + f.lo < before ? 1u : 0u;
    if (f.hi + carry) hi_.fetch_add(f.hi + carry, std::memory_order_relaxed);
  }
  // Read only when no thread adds (between passes).
  FixedTotal total() const { return {lo_.load(std::memory_order_relaxed), hi_.load(std::memory_order_relaxed)}; }
  void set(FixedTotal t) {
    lo_.store(t.lo, std::memory_order_relaxed);
    hi_.store(t.hi, std::memory_order_relaxed);
  }
  double value() const { return total().value(); }

  static FixedTotal to_fixed(double v) {
    const double scaled = std::fmin(v, 0x1p68) * 0x1p32;  // exact: a power-of-two scale
    const double hi = std::floor(scaled * 0x1p-64);
    const double lo = scaled - hi * 0x1p64;  // exact: the bits of `scaled` below 2^64
    return {uint64_t(lo), uint64_t(hi)};
  }

 private:
  std::atomic<uint64_t> lo_{0}, hi_{0};
};

}  // namespace caligo
