// Where a ray o + t d is inside the convex solids that bound shapes, volumes and lights, each
// test written once for the scalar callers (core/ray_solids_lanes.h has 8-lane float versions
// of the ball, cone and oriented box for the real-time light volumes; the real-time media
// overlaps in realtime/media_simd.h and accumulate_lanes.h keep their own segment forms).
// Each returns the part of [tmin, tmax] inside the solid as a RayRange, nullopt when empty;
// `dir` need not be unit unless a function says so. Pure and thread-safe.
//
// One policy for rays parallel to a box face: a zero direction component leaves that slab
// all (origin inside it, faces included) or nothing.
#pragma once

#include <array>
#include <optional>

#include "core/bounds.h"
#include "core/ray.h"
#include "core/ray_range.h"
#include "core/vec.h"

namespace caligo {

// Both roots of |o + t d - centre| = radius in the ray's own parameter, unclipped (t0 <= t1);
// nullopt when the line misses or d is zero. The discriminant is formed from the point of
// closest approach, which loses far less precision than b^2 - ac for distant origins (Haines
// et al., Ray Tracing Gems, ch. 7); the roots use the stable q form.
std::optional<RayRange> sphere_roots(Vec3 origin, Vec3 dir, Vec3 centre, float radius);

// The ball |p - centre| <= radius.
std::optional<RayRange> ray_ball(Vec3 origin, Vec3 dir, Vec3 centre, float radius, float tmin, float tmax);

// The pieces of {t : a t^2 + 2 b t + c >= 0}: at most two intervals, ends +-1e300 where
// unbounded. |a| below 1e-12 counts as 0 (callers' a are differences of squared cosines of
// unit vectors, so the threshold is relative).
struct QuadraticPieces {
  int count = 0;
  double lo[2], hi[2];
};
QuadraticPieces quadratic_nonnegative(double a, double b, double c);

// One nappe of a cone, {p : dot(p - apex, axis) >= cos_half |p - apex|} (axis and dir unit),
// in double. A half-angle of 90 degrees or more (cos_half <= 0) is not convex: all of
// [tmin, tmax] (conservative).
std::optional<RayRange> ray_cone(Vec3 origin, Vec3 dir, Vec3 apex, Vec3 axis, float cos_half, float tmin,
                                 float tmax);

// The open half-space dot(p - on_plane, normal) > 0, in double: a ray crossing the plane gets
// the range up to (or from) the crossing, a ray lying in the plane gets nothing.
std::optional<RayRange> ray_half_space(Vec3 origin, Vec3 dir, Vec3 on_plane, Vec3 normal, float tmin,
                                       float tmax);

// The axis-aligned box [lo, hi] (slab test, faces included).
std::optional<RayRange> ray_box(Vec3 origin, Vec3 dir, Vec3 lo, Vec3 hi, float tmin, float tmax);

// The same for a ray's own range [ray.tmin, ray.tmax].
inline std::optional<RayRange> ray_box(const Ray& ray, const Bounds3& box) {
  return ray_box(ray.origin, ray.direction, box.lo, box.hi, ray.tmin, ray.tmax);
}

// A box in its own orthonormal frame: the points origin + sum_i u_i axes[i] with lo <= u <= hi.
struct OrientedBox {
  Vec3 origin;
  std::array<Vec3, 3> axes;  // orthonormal
  Vec3 lo, hi;
};
std::optional<RayRange> ray_oriented_box(Vec3 origin, Vec3 dir, const OrientedBox& box, float tmin, float tmax);

}  // namespace caligo
