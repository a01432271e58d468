// A ray with its valid parameter range [tmin, tmax).
#pragma once

#include "core/math.h"
#include "core/vec.h"

namespace caligo {

struct Ray {
  Vec3 origin;
  Vec3 direction;  // not necessarily unit length; t is measured in units of |direction|
  float tmin = 0.0f;
  float tmax = kInfinity;

  Vec3 at(float t) const { return origin + direction * t; }
};

// Offsets a ray origin off a surface along its geometric normal, on the side of `w`, so the
// new ray does not re-hit the surface it leaves. Scaled with the point's magnitude because
// float error in a hit point grows with its distance from the origin.
inline Vec3 offset_ray_origin(Vec3 p, Vec3 ng, Vec3 w) {
  const float scale =
      1e-4f * std::max(1.0f, max_component(Vec3(std::abs(p.x), std::abs(p.y), std::abs(p.z))));
  const Vec3 offset = ng * scale;
  return dot(w, ng) > 0.0f ? p + offset : p - offset;
}

}  // namespace caligo
