// light_volume.h's light_volume_interval for 8 camera rays at once (xsimd, AVX2), in float.
// The accumulation pass asks it for every pixel of a light's screen rectangle, most of
// which miss a narrow spot's cone, so the per-pixel double-precision test was a quarter of
// the pass.
//
// Float is exact enough wherever the quadratic is well conditioned; the few lanes where it
// is not (rays grazing a cone's surface or parallel to it, rays through the apex region,
// near-tangent spheres) come back flagged `unsure` and the caller takes light_volume.h's
// scalar double answer for them. Elsewhere the interval ends agree with the scalar ones to
// float rounding (light_volume_simd_test.cpp), and samples there carry no light anyway: the
// cone's smoothstep and the range window are 0 at the volume's surface. Prepared once per
// light and frame; read-only afterwards (thread-safe).
#pragma once

#include <xsimd/xsimd.hpp>

#include "core/vec.h"
#include "lights/light.h"

namespace caligo {

class LightVolumeLanes {
 public:
  using Batch = xsimd::batch<float>;
  using Mask = xsimd::batch_bool<float>;

  explicit LightVolumeLanes(const Light& light);

  struct Result {
    Batch t0, t1;  // the interval within [0, tmax] where `hit`
    Mask hit;      // non-empty (t0 <= t1), as light_volume_interval's has_value()
    Mask unsure;   // float cannot decide: use the scalar light_volume_interval for these lanes
  };
  // Rays origin + t dir (dir unit), t in [0, tmax], one per lane.
  Result intervals(const Batch& ox, const Batch& oy, const Batch& oz, const Batch& dx, const Batch& dy,
                   const Batch& dz, const Batch& tmax) const;

 private:
  enum class Kind { none, whole, sphere, cone, box };
  Kind kind_ = Kind::none;
  bool range_sphere_ = false;  // cones: also cut by the range sphere
  Vec3 centre_;                // sphere centre, cone apex, box light position
  float radius_ = 0.0f;
  Vec3 axis_;  // cone axis
  float cos2_ = 0.0f;
  Vec3 box_axes_[3];  // box light: right, up, direction
  float box_lo_[3] = {}, box_hi_[3] = {};

  void sphere(const Batch& ox, const Batch& oy, const Batch& oz, const Batch& dx, const Batch& dy,
              const Batch& dz, const Batch& tmax, Result& r) const;
  void cone(const Batch& ox, const Batch& oy, const Batch& oz, const Batch& dx, const Batch& dy,
            const Batch& dz, const Batch& tmax, Result& r) const;
  void box(const Batch& ox, const Batch& oy, const Batch& oz, const Batch& dx, const Batch& dy,
           const Batch& dz, const Batch& tmax, Result& r) const;
};

}  // namespace caligo
