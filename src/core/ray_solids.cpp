#include "core/ray_solids.h"

#include <cmath>
#include <utility>

namespace caligo {

std::optional<RayRange> sphere_roots(Vec3 origin, Vec3 dir, Vec3 centre, float radius) {
  const Vec3 o = origin - centre;
  const float a = dot(dir, dir);
  if (!(a > 0.0f)) return std::nullopt;
  const float r2 = radius * radius;
  const float b = dot(o, dir);
  const float c = dot(o, o) - r2;
  const Vec3 l = o - dir * (b / a);
  const float disc = a * (r2 - dot(l, l));
  if (disc < 0.0f) return std::nullopt;
  const float q = -(b + std::copysign(std::sqrt(disc), b));
  float t0 = q / a;
  float t1 = q != 0.0f ? c / q : -t0;
  if (t0 > t1) std::swap(t0, t1);
  return RayRange{t0, t1};
}

std::optional<RayRange> ray_ball(Vec3 origin, Vec3 dir, Vec3 centre, float radius, float tmin, float tmax) {
  const auto roots = sphere_roots(origin, dir, centre, radius);
  if (!roots) return std::nullopt;
  return clip_range(roots->t0, roots->t1, tmin, tmax);
}

QuadraticPieces quadratic_nonnegative(double a, double b, double c) {
  constexpr double kInf = 1e300;
  QuadraticPieces p;
  const auto add = [&p](double lo, double hi) {
    p.lo[p.count] = lo;
    p.hi[p.count] = hi;
    ++p.count;
  };
  if (std::abs(a) < 1e-12) {  // linear: 2 b t + c >= 0
    if (b > 0.0) add(-c / (2.0 * b), kInf);
    else if (b < 0.0) add(-kInf, -c / (2.0 * b));
    else if (c >= 0.0) add(-kInf, kInf);
    return p;
  }
  const double disc = b * b - a * c;
  if (disc < 0.0) {
    if (a > 0.0) add(-kInf, kInf);
    return p;
  }
  // Roots without cancellation in b + sign(b) sqrt(disc).
  const double q = -(b + std::copysign(std::sqrt(disc), b));
  double r0 = q / a, r1 = q != 0.0 ? c / q : r0;
  if (r0 > r1) std::swap(r0, r1);
  if (a > 0.0) {
    add(-kInf, r0);
    add(r1, kInf);
  } else {
    add(r0, r1);
  }
  return p;
}

std::optional<RayRange> ray_cone(Vec3 origin, Vec3 dir, Vec3 apex, Vec3 axis, float cos_half, float tmin,
                                 float tmax) {
  if (cos_half <= 0.0f) return clip_range(tmin, tmax, tmin, tmax);
  // Inside the double cone where f(t) = (v.axis)^2 - cos^2 |v|^2 >= 0, v = origin - apex + t dir;
  // the nappe is where v.axis >= 0. A convex set meets a line in one interval, so of the (at
  // most two) pieces of f >= 0 only one survives the half-space.
  const double cos2 = double(cos_half) * cos_half;
  const Vec3 v = origin - apex;
  const double da = dot(dir, axis), va = dot(v, axis);
  const QuadraticPieces pieces = quadratic_nonnegative(da * da - cos2, da * va - cos2 * double(dot(dir, v)),
                                                       va * va - cos2 * double(length_squared(v)));
  // Half-space v.axis >= 0: t >= -va/da (da > 0), t <= -va/da (da < 0), all or nothing (da = 0).
  double h0 = -1e300, h1 = 1e300;
  if (da > 0.0) h0 = -va / da;
  else if (da < 0.0) h1 = -va / da;
  else if (va < 0.0) return std::nullopt;
  std::optional<RayRange> hull;
  for (int i = 0; i < pieces.count; ++i) {
    const auto piece = clip_range(std::max(pieces.lo[i], h0), std::min(pieces.hi[i], h1), tmin, tmax);
    if (!piece) continue;
    // Two survivors only where both touch the apex (a single point): keep their hull.
    hull = hull ? RayRange{std::min(hull->t0, piece->t0), std::max(hull->t1, piece->t1)} : *piece;
  }
  return hull;
}

std::optional<RayRange> ray_half_space(Vec3 origin, Vec3 dir, Vec3 on_plane, Vec3 normal, float tmin,
                                       float tmax) {
  const double side = dot(origin - on_plane, normal), rate = dot(dir, normal);
  if (rate > 0.0) return clip_range(-side / rate, 1e300, tmin, tmax);
  if (rate < 0.0) return clip_range(-1e300, -side / rate, tmin, tmax);
  return side > 0.0 ? clip_range(tmin, tmax, tmin, tmax) : std::nullopt;
}

std::optional<RayRange> ray_box(Vec3 origin, Vec3 dir, Vec3 lo, Vec3 hi, float tmin, float tmax) {
  float t0 = tmin, t1 = tmax;
  for (int a = 0; a < 3; ++a) {
    if (dir[a] == 0.0f) {
      if (!(origin[a] >= lo[a] && origin[a] <= hi[a])) return std::nullopt;
      continue;
    }
    const float inv = 1.0f / dir[a];
    float tn = (lo[a] - origin[a]) * inv, tf = (hi[a] - origin[a]) * inv;
    if (tn > tf) std::swap(tn, tf);
    t0 = std::max(t0, tn);
    t1 = std::min(t1, tf);
  }
  if (!(t0 <= t1)) return std::nullopt;
  return RayRange{t0, t1};
}

std::optional<RayRange> ray_oriented_box(Vec3 origin, Vec3 dir, const OrientedBox& box, float tmin, float tmax) {
  const Vec3 rel = origin - box.origin;
  const Vec3 o(dot(rel, box.axes[0]), dot(rel, box.axes[1]), dot(rel, box.axes[2]));
  const Vec3 d(dot(dir, box.axes[0]), dot(dir, box.axes[1]), dot(dir, box.axes[2]));
  return ray_box(o, d, box.lo, box.hi, tmin, tmax);
}

}  // namespace caligo
