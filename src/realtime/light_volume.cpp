#include "realtime/light_volume.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace caligo {
namespace {

std::optional<TInterval> clipped(double t0, double t1, float tmin, float tmax) {
  const float a = std::max(float(t0), tmin), b = std::min(float(t1), tmax);
  if (!(a <= b)) return std::nullopt;
  return TInterval{a, b};
}

std::optional<TInterval> intersect(std::optional<TInterval> a, std::optional<TInterval> b) {
  if (!a || !b) return std::nullopt;
  return clipped(std::max(a->t0, b->t0), std::min(a->t1, b->t1), -kInfinity, kInfinity);
}

// Both pieces of {t : f(t) >= 0} for f = a t^2 + 2 b t + c, as up to two intervals.
struct QuadraticPieces {
  int count = 0;
  double lo[2], hi[2];
  void add(double l, double h) {
    lo[count] = l;
    hi[count] = h;
    ++count;
  }
};

QuadraticPieces nonnegative_pieces(double a, double b, double c) {
  QuadraticPieces p;
  constexpr double kInf = 1e300;
  // A relative threshold: a is a difference of squared cosines of unit vectors.
  if (std::abs(a) < 1e-12) {
    if (std::abs(b) < 1e-300) {
      if (c >= 0.0) p.add(-kInf, kInf);
    } else if (b > 0.0) {
      p.add(-c / (2.0 * b), kInf);
    } else {
      p.add(-kInf, -c / (2.0 * b));
    }
    return p;
  }
  const double disc = b * b - a * c;
  if (disc < 0.0) {
    if (a > 0.0) p.add(-kInf, kInf);
    return p;
  }
  // Numerically stable roots (no cancellation in b + sign(b) sqrt(disc)).
  const double q = -(b + std::copysign(std::sqrt(disc), b));
  double r0 = q / a, r1 = q != 0.0 ? c / q : r0;
  if (r0 > r1) std::swap(r0, r1);
  if (a > 0.0) {
    p.add(-kInf, r0);
    p.add(r1, kInf);
  } else {
    p.add(r0, r1);
  }
  return p;
}

}  // namespace

std::optional<TInterval> ray_sphere_interval(Vec3 origin, Vec3 dir, Vec3 centre, float radius, float tmin,
                                             float tmax) {
  // Relative to the closest point, which keeps the discriminant accurate far from the sphere.
  const Vec3 oc = origin - centre;
  const double b = dot(oc, dir);
  const Vec3 closest = oc - dir * float(b);
  const double h = double(radius) * radius - double(length_squared(closest));
  if (h < 0.0) return std::nullopt;
  const double s = std::sqrt(h);
  return clipped(-b - s, -b + s, tmin, tmax);
}

std::optional<TInterval> ray_cone_interval(Vec3 origin, Vec3 dir, Vec3 apex, Vec3 axis, float cos_half,
                                           float tmin, float tmax) {
  if (cos_half <= 0.0f) return clipped(tmin, tmax, tmin, tmax);
  // Inside the double cone: f(t) = (v.axis)^2 - cos^2 |v|^2 >= 0 with v = o - apex + t d;
  // the nappe is the part where v.axis >= 0. A convex set meets a line in one interval, so
  // of the (at most two) pieces of f >= 0 only one survives the half-space.
  const double cos2 = double(cos_half) * cos_half;
  const Vec3 v = origin - apex;
  const double da = dot(dir, axis), va = dot(v, axis);
  const double a = da * da - cos2;
  const double b = da * va - cos2 * double(dot(dir, v));
  const double c = va * va - cos2 * double(length_squared(v));
  const QuadraticPieces pieces = nonnegative_pieces(a, b, c);
  // Half-space v.axis >= 0: t >= -va/da (da > 0), t <= -va/da (da < 0), all or nothing (da = 0).
  double h0 = -1e300, h1 = 1e300;
  if (da > 0.0)
    h0 = -va / da;
  else if (da < 0.0)
    h1 = -va / da;
  else if (va < 0.0)
    return std::nullopt;
  std::optional<TInterval> best;
  for (int i = 0; i < pieces.count; ++i) {
    const double lo = std::max(pieces.lo[i], h0), hi = std::min(pieces.hi[i], h1);
    if (lo > hi) continue;
    const auto piece = clipped(lo, hi, tmin, tmax);
    if (!piece) continue;
    // Two survivors only at the apex (a single point); keep their hull.
    best = best ? TInterval{std::min(best->t0, piece->t0), std::max(best->t1, piece->t1)} : *piece;
  }
  return best;
}

std::optional<TInterval> ray_box_light_interval(Vec3 origin, Vec3 dir, const BoxLight& light, float tmin,
                                                float tmax) {
  const Vec3 right = cross(light.direction, light.up);
  const Vec3 axes[3] = {right, light.up, light.direction};
  const float lo[3] = {-light.half_width, -light.half_height, 0.0f};
  const float hi[3] = {light.half_width, light.half_height, light.range};
  const Vec3 rel = origin - light.position;
  float t0 = tmin, t1 = tmax;
  for (int a = 0; a < 3; ++a) {
    const float o = dot(rel, axes[a]), d = dot(dir, axes[a]);
    if (d == 0.0f) {
      if (o < lo[a] || o > hi[a]) return std::nullopt;
      continue;
    }
    float tn = (lo[a] - o) / d, tf = (hi[a] - o) / d;
    if (tn > tf) std::swap(tn, tf);
    t0 = std::max(t0, tn);
    t1 = std::min(t1, tf);
  }
  if (!(t0 <= t1)) return std::nullopt;
  return TInterval{t0, t1};
}

namespace {

struct LightVolume {
  Vec3 o, d;
  float tmin, tmax;
  std::optional<TInterval> operator()(const PointLight& l) const {
    if (!std::isfinite(l.range)) return clipped(tmin, tmax, tmin, tmax);
    return ray_sphere_interval(o, d, l.position, l.range, tmin, tmax);
  }
  std::optional<TInterval> operator()(const SpotLight& l) const {
    const auto cone = ray_cone_interval(o, d, l.position, l.direction, l.cos_outer, tmin, tmax);
    if (!std::isfinite(l.range)) return cone;
    return intersect(cone, ray_sphere_interval(o, d, l.position, l.range, tmin, tmax));
  }
  std::optional<TInterval> operator()(const BoxLight& l) const {
    return ray_box_light_interval(o, d, l, tmin, tmax);
  }
  std::optional<TInterval> operator()(const DirectionalLight&) const {
    return clipped(tmin, tmax, tmin, tmax);
  }
  // Area and environment lights are not part of the real-time volumetric pipeline.
  std::optional<TInterval> operator()(const SphereLight&) const { return std::nullopt; }
  std::optional<TInterval> operator()(const QuadLight&) const { return std::nullopt; }
  std::optional<TInterval> operator()(const TriangleLight&) const { return std::nullopt; }
  std::optional<TInterval> operator()(const EnvironmentLight&) const { return std::nullopt; }
};

}  // namespace

std::optional<TInterval> light_volume_interval(const Light& light, Vec3 origin, Vec3 dir, float tmin,
                                               float tmax) {
  return std::visit(LightVolume{origin, dir, tmin, tmax}, light);
}

namespace {

// Corners whose convex hull contains the light's volume; empty for unbounded volumes.
struct VolumeCorners {
  std::vector<Vec3>& out;
  void box(Vec3 c, Vec3 a, Vec3 b, Vec3 d) const {  // c +- a +- b +- d
    for (int i = 0; i < 8; ++i)
      out.push_back(c + a * (i & 1 ? 1.0f : -1.0f) + b * (i & 2 ? 1.0f : -1.0f) + d * (i & 4 ? 1.0f : -1.0f));
  }
  void sphere(Vec3 c, float r) const { box(c, {r, 0, 0}, {0, r, 0}, {0, 0, r}); }
  void operator()(const PointLight& l) const {
    if (std::isfinite(l.range)) sphere(l.position, l.range);
  }
  void operator()(const SpotLight& l) const {
    if (!std::isfinite(l.range)) return;
    // Narrow cones: the apex and the square around the cone's section at axial distance
    // `range` (the cone cut by the range sphere lies within that truncated cone).
    if (l.cos_outer < 0.5f) return sphere(l.position, l.range);
    const float r = l.range * std::sqrt(1.0f - l.cos_outer * l.cos_outer) / l.cos_outer;
    const Frame f = Frame::from_z(l.direction);
    out.push_back(l.position);
    for (int i = 0; i < 4; ++i)
      out.push_back(l.position + l.direction * l.range + f.s * (i & 1 ? r : -r) + f.t * (i & 2 ? r : -r));
  }
  void operator()(const BoxLight& l) const {
    const Vec3 right = cross(l.direction, l.up);
    box(l.position + l.direction * (0.5f * l.range), right * l.half_width, l.up * l.half_height,
        l.direction * (0.5f * l.range));
  }
  void operator()(const DirectionalLight&) const {}
  void operator()(const SphereLight&) const {}
  void operator()(const QuadLight&) const {}
  void operator()(const TriangleLight&) const {}
  void operator()(const EnvironmentLight&) const {}
};

}  // namespace

PixelRect light_screen_bounds(const Light& light, const View& view) {
  const PixelRect all{0, 0, view.resolution.x, view.resolution.y};
  std::vector<Vec3> corners;
  std::visit(VolumeCorners{corners}, light);
  if (corners.empty()) return all;
  float x0 = kInfinity, y0 = kInfinity, x1 = -kInfinity, y1 = -kInfinity;
  for (Vec3 c : corners) {
    const Vec3 q = view.project(c);
    // A corner at or behind the eye plane projects nowhere useful: keep the whole image.
    if (view.projection == Projection::perspective && !(q.z > 1e-4f)) return all;
    x0 = std::min(x0, q.x);
    y0 = std::min(y0, q.y);
    x1 = std::max(x1, q.x);
    y1 = std::max(y1, q.y);
  }
  // Pixel x is inside when its centre x + 0.5 lies in [x0, x1]; one pixel of slack for rounding.
  auto lo = [](float v, int n) { return int(std::clamp(std::floor(v - 0.5f) - 1.0f, 0.0f, float(n))); };
  auto hi = [](float v, int n) { return int(std::clamp(std::ceil(v - 0.5f) + 2.0f, 0.0f, float(n))); };
  return {lo(x0, view.resolution.x), lo(y0, view.resolution.y), hi(x1, view.resolution.x),
          hi(y1, view.resolution.y)};
}

}  // namespace caligo
