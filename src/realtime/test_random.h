// Random points and directions for the real-time tests (test-only; not in the library).
#pragma once

#include <cmath>

#include "core/rng.h"
#include "core/vec.h"

namespace caligo::testing {

inline Vec3 random_in_cube(Pcg32& rng, float half) {
  return {(rng.next_float() * 2.0f - 1.0f) * half, (rng.next_float() * 2.0f - 1.0f) * half,
          (rng.next_float() * 2.0f - 1.0f) * half};
}

// Uniform on the sphere, by rejection from the cube.
inline Vec3 random_direction(Pcg32& rng) {
  for (;;) {
    const Vec3 v = random_in_cube(rng, 1.0f);
    const float l2 = length_squared(v);
    if (l2 > 1e-4f && l2 <= 1.0f) return v / std::sqrt(l2);
  }
}

}  // namespace caligo::testing
