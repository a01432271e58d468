// Random rays and a brute-force check of ray–solid ranges, for tests only (core/ray_solids.h
// and the light volumes built on it).
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <optional>

#include "core/ray_range.h"
#include "core/rng.h"
#include "core/vec.h"

namespace caligo::testing {

inline Vec3 random_in_cube(Pcg32& rng, float half) {
  return {(2.0f * rng.next_float() - 1.0f) * half, (2.0f * rng.next_float() - 1.0f) * half,
          (2.0f * rng.next_float() - 1.0f) * half};
}

// Uniform on the sphere, by rejection from the cube.
inline Vec3 random_direction(Pcg32& rng) {
  for (;;) {
    const Vec3 v = random_in_cube(rng, 1.0f);
    const float l2 = length_squared(v);
    if (l2 > 1e-4f && l2 <= 1.0f) return v / std::sqrt(l2);
  }
}

// Brute force: the first and last of kSteps dense samples along [tmin, tmax] where `inside`
// holds. The analytic interval must contain every inside sample and start/end within one
// sample spacing of the first/last one (the sets are convex, so there are no gaps).
inline void expect_matches_brute_force(const std::function<bool(Vec3)>& inside, Vec3 o, Vec3 d, float tmin,
                                       float tmax, std::optional<RayRange> got, int ray) {
  constexpr int kSteps = 20000;
  const float dt = (tmax - tmin) / kSteps;
  float first = kInfinity, last = -kInfinity;
  for (int i = 0; i <= kSteps; ++i) {
    const float t = tmin + dt * float(i);
    if (inside(o + d * t)) {
      first = std::min(first, t);
      last = std::max(last, t);
    }
  }
  if (first == kInfinity) {
    // Nothing sampled inside: the interval may only be a sliver thinner than the spacing.
    if (got) {
      EXPECT_LT(got->t1 - got->t0, 2.0f * dt) << "ray " << ray;
    }
    return;
  }
  ASSERT_TRUE(got.has_value()) << "ray " << ray << " brute force [" << first << ", " << last << "]";
  const float tol = dt * 1.01f + 1e-4f;
  EXPECT_LE(got->t0, first + 1e-4f) << "ray " << ray;
  EXPECT_GE(got->t1, last - 1e-4f) << "ray " << ray;
  EXPECT_GT(got->t0, first - tol) << "ray " << ray;
  EXPECT_LT(got->t1, last + tol) << "ray " << ray;
}

}  // namespace caligo::testing
