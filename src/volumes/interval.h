// A volume primitive's stretch of a ray: the seed's `{t0, t1, primID}`, with the bound of the
// extinction over it. Intervals of different primitives may overlap (volume primitives are
// additive); one primitive's intervals never do. A sparse grid yields one interval per run
// of occupied blocks whose majorants agree, a mesh volume one per inside stretch, an
// analytic shape one.
#pragma once

#include <cstdint>

#include "core/rgb.h"

namespace caligo {

struct VolumeInterval {
  float t0, t1;        // t0 < t1, in the ray's parameter
  uint32_t primitive;  // index into the scene's volume primitives
  RGB sigma_maj;       // 1/m: bounds the primitive's sigma_t everywhere on [t0, t1]
  bool homogeneous;    // the primitive's coefficients are constant on [t0, t1]: one march step
  RGB sigma_min{};     // 1/m: below the primitive's sigma_t everywhere on [t0, t1] (0: unknown)
};

}  // namespace caligo
