// A stretch of a ray: the parameters [t0, t1] (t0 <= t1) where the ray is inside something.
// The one range type of every ray–solid test (core/ray_solids.h), the light volumes and the
// volume intervals; an empty range is std::nullopt, never t0 > t1.
#pragma once

#include <algorithm>
#include <optional>

namespace caligo {

struct RayRange {
  float t0, t1;  // t0 <= t1
};

// [lo, hi] ∩ [tmin, tmax], rounded to float; nullopt when empty (or NaN). The ends come in
// double so that callers computing them in double round once.
inline std::optional<RayRange> clip_range(double lo, double hi, float tmin, float tmax) {
  const float a = std::max(float(lo), tmin), b = std::min(float(hi), tmax);
  if (!(a <= b)) return std::nullopt;
  return RayRange{a, b};
}

// The overlap of two ranges; nullopt when either is empty or they do not meet.
inline std::optional<RayRange> overlap(std::optional<RayRange> a, std::optional<RayRange> b) {
  if (!a || !b) return std::nullopt;
  return clip_range(std::max(a->t0, b->t0), std::min(a->t1, b->t1), a->t0, a->t1);
}

}  // namespace caligo
