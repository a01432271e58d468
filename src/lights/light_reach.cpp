#include "lights/light_reach.h"

#include <algorithm>
#include <cmath>

namespace caligo {
namespace {

std::optional<RayInterval> clip(double lo, double hi, float tmin, float tmax) {
  const float a = float(std::max(lo, double(tmin))), b = float(std::min(hi, double(tmax)));
  if (!(a <= b)) return std::nullopt;
  return RayInterval{a, b};
}

std::optional<RayInterval> intersect(std::optional<RayInterval> a, std::optional<RayInterval> b) {
  if (!a || !b) return std::nullopt;
  return clip(std::max(a->t0, b->t0), std::min(a->t1, b->t1), a->t0, a->t1);
}

// The (at most two) intervals where a t^2 + 2 b t + c >= 0.
struct Pieces {
  int count = 0;
  double lo[2], hi[2];
};

Pieces nonnegative(double a, double b, double c) {
  constexpr double kInf = 1e300;
  Pieces p;
  const auto add = [&](double lo, double hi) {
    p.lo[p.count] = lo;
    p.hi[p.count] = hi;
    ++p.count;
  };
  if (a == 0.0) {
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
  // Roots without cancellation.
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

struct Reach {
  Vec3 o, d;
  float tmin, tmax;

  std::optional<RayInterval> all() const { return clip(tmin, tmax, tmin, tmax); }
  std::optional<RayInterval> range(Vec3 centre, float r) const {
    return std::isfinite(r) ? ray_ball_reach(o, d, centre, r, tmin, tmax) : all();
  }
  std::optional<RayInterval> operator()(const PointLight& l) const { return range(l.position, l.range); }
  std::optional<RayInterval> operator()(const SpotLight& l) const {
    return intersect(ray_cone_reach(o, d, l.position, l.direction, l.cos_outer, tmin, tmax),
                     range(l.position, l.range));
  }
  std::optional<RayInterval> operator()(const QuadLight& l) const {
    if (l.two_sided) return all();
    return ray_half_space_reach(o, d, l.corner, cross(l.edge1, l.edge2), tmin, tmax);
  }
  std::optional<RayInterval> operator()(const TriangleLight& l) const {
    if (l.two_sided) return all();
    return ray_half_space_reach(o, d, l.p0, cross(l.p1 - l.p0, l.p2 - l.p0), tmin, tmax);
  }
  std::optional<RayInterval> operator()(const SphereLight&) const { return all(); }
  std::optional<RayInterval> operator()(const BoxLight&) const { return all(); }
  std::optional<RayInterval> operator()(const DirectionalLight&) const { return all(); }
  std::optional<RayInterval> operator()(const EnvironmentLight&) const { return all(); }
};

}  // namespace

std::optional<RayInterval> ray_cone_reach(Vec3 origin, Vec3 dir, Vec3 apex, Vec3 axis, float cos_half,
                                          float tmin, float tmax) {
  if (cos_half <= 0.0f) return clip(tmin, tmax, tmin, tmax);
  // Inside the double cone where f(t) = (v.axis)^2 - cos^2 |v|^2 >= 0, v = origin - apex + t dir;
  // the nappe is where v.axis >= 0. A convex set meets a line in one interval.
  const double cos2 = double(cos_half) * cos_half;
  const Vec3 v = origin - apex;
  const double da = dot(dir, axis), va = dot(v, axis);
  const Pieces pieces = nonnegative(da * da - cos2, da * va - cos2 * double(dot(dir, v)),
                                    va * va - cos2 * double(length_squared(v)));
  double h0 = -1e300, h1 = 1e300;
  if (da > 0.0) h0 = -va / da;
  else if (da < 0.0) h1 = -va / da;
  else if (va < 0.0) return std::nullopt;
  std::optional<RayInterval> hull;
  for (int i = 0; i < pieces.count; ++i) {
    const auto piece = clip(std::max(pieces.lo[i], h0), std::min(pieces.hi[i], h1), tmin, tmax);
    if (!piece) continue;
    // Two survivors only where both touch the apex: keep their hull.
    hull = hull ? RayInterval{std::min(hull->t0, piece->t0), std::max(hull->t1, piece->t1)} : *piece;
  }
  return hull;
}

std::optional<RayInterval> ray_ball_reach(Vec3 origin, Vec3 dir, Vec3 centre, float radius, float tmin,
                                          float tmax) {
  const Vec3 v = origin - centre;
  const Pieces p = nonnegative(-1.0, -double(dot(dir, v)), double(radius) * radius - double(length_squared(v)));
  if (p.count == 0) return std::nullopt;
  return clip(p.lo[0], p.hi[0], tmin, tmax);
}

std::optional<RayInterval> ray_half_space_reach(Vec3 origin, Vec3 dir, Vec3 on_plane, Vec3 normal, float tmin,
                                                float tmax) {
  const double side = dot(origin - on_plane, normal), rate = dot(dir, normal);
  if (rate > 0.0) return clip(-side / rate, 1e300, tmin, tmax);
  if (rate < 0.0) return clip(-1e300, -side / rate, tmin, tmax);
  return side > 0.0 ? clip(tmin, tmax, tmin, tmax) : std::nullopt;
}

std::optional<RayInterval> light_reach(const Light& light, Vec3 origin, Vec3 dir, float tmin, float tmax) {
  return std::visit(Reach{origin, dir, tmin, tmax}, light);
}

}  // namespace caligo
