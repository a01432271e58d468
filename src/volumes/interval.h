// A volume primitive's stretch of a ray: the seed's `{t0, t1, primID}`. Intervals of
// different primitives may overlap (volume primitives are additive).
#pragma once

#include <cstdint>

namespace caligo {

struct VolumeInterval {
  float t0, t1;        // t0 < t1, in the ray's parameter
  uint32_t primitive;  // index into the scene's volume primitives
};

}  // namespace caligo
