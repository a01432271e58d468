// core/ray_solids.h's ball, cone and oriented box for 8 rays at once (xsimd, AVX2), in float,
// for the real-time passes (realtime/light_volume_simd.h asks them for every pixel of a
// light's screen rectangle, most of which miss a narrow spot's cone).
//
// Float is exact enough wherever the test is well conditioned; the few lanes where it is not
// (rays grazing a cone's surface or parallel to it, rays through the apex region,
// near-tangent spheres) come back flagged `unsure`, and the caller takes the scalar answer for
// them. Elsewhere the ends agree with the scalar ones to float rounding
// (realtime/light_volume_simd_test.cpp). The box needs no flag: it is the scalar slab test's
// float arithmetic lane by lane.
#pragma once

#include <xsimd/xsimd.hpp>

#include "core/ray_solids.h"
#include "core/vec.h"

namespace caligo::lanes {

using Batch = xsimd::batch<float>;
using Mask = xsimd::batch_bool<float>;

// One ray per lane: origin + t dir, dir unit, t in [0, tmax].
struct Rays {
  Batch ox, oy, oz, dx, dy, dz, tmax;
};

// Per lane: the range [t0, t1] where `hit`; `unsure` where float cannot decide.
struct Ranges {
  Batch t0, t1;
  Mask hit, unsure;
};

// All of [0, tmax] (for every lane whose tmax is not negative).
inline Ranges whole(const Rays& r) { return {Batch(0.0f), r.tmax, Batch(0.0f) <= r.tmax, Mask(false)}; }

// ray_ball.
Ranges ray_ball(const Rays& r, Vec3 centre, float radius);
// ray_cone with cos2 = cos_half^2 (cos_half > 0; callers take whole() otherwise).
Ranges ray_cone(const Rays& r, Vec3 apex, Vec3 axis, float cos2);
// ray_oriented_box.
Ranges ray_oriented_box(const Rays& r, const OrientedBox& box);
// Both ranges: the overlap, unsure where either is.
Ranges overlap(const Ranges& a, const Ranges& b);

}  // namespace caligo::lanes
