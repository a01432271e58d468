// Axis-aligned bounding boxes.
#pragma once

#include <algorithm>

#include "core/math.h"
#include "core/ray.h"
#include "core/vec.h"

namespace caligo {

struct Bounds3 {
  Vec3 lo{kInfinity, kInfinity, kInfinity};
  Vec3 hi{-kInfinity, -kInfinity, -kInfinity};

  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  void extend(Vec3 p) {
    lo = min(lo, p);
    hi = max(hi, p);
  }
  void extend(const Bounds3& b) {
    lo = min(lo, b.lo);
    hi = max(hi, b.hi);
  }
  Vec3 diagonal() const { return hi - lo; }
  Vec3 center() const { return (lo + hi) * 0.5f; }
  bool contains(Vec3 p) const {
    return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y && p.z >= lo.z && p.z <= hi.z;
  }
  // Slab test; returns the parametric overlap of the ray with the box clipped to [tmin, tmax].
  bool intersect(const Ray& ray, float* t0_out, float* t1_out) const {
    float t0 = ray.tmin, t1 = ray.tmax;
    for (int a = 0; a < 3; ++a) {
      const float inv = 1.0f / ray.direction[a];
      float tn = (lo[a] - ray.origin[a]) * inv;
      float tf = (hi[a] - ray.origin[a]) * inv;
      if (tn > tf) std::swap(tn, tf);
      t0 = tn > t0 ? tn : t0;
      t1 = tf < t1 ? tf : t1;
      if (t0 > t1) return false;
    }
    *t0_out = t0;
    *t1_out = t1;
    return true;
  }
};

}  // namespace caligo
