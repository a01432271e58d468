#include "lights/light_reach.h"

#include <cmath>

namespace caligo {

std::optional<RayRange> LightReach::all() const { return clip_range(tmin, tmax, tmin, tmax); }

std::optional<RayRange> LightReach::within(Vec3 centre, float range) const {
  return std::isfinite(range) ? ray_ball(origin, dir, centre, range, tmin, tmax) : all();
}

std::optional<RayRange> LightReach::operator()(const PointLight& l) const { return within(l.position, l.range); }

std::optional<RayRange> LightReach::operator()(const SpotLight& l) const {
  const auto cone = ray_cone(origin, dir, l.position, l.direction, l.cos_outer, tmin, tmax);
  return std::isfinite(l.range) ? overlap(cone, within(l.position, l.range)) : cone;
}

std::optional<RayRange> LightReach::operator()(const BoxLight& l) const {
  return ray_oriented_box(origin, dir, light_box(l), tmin, tmax);
}

std::optional<RayRange> LightReach::operator()(const QuadLight& l) const {
  if (l.two_sided) return all();
  return ray_half_space(origin, dir, l.corner, cross(l.edge1, l.edge2), tmin, tmax);
}

std::optional<RayRange> LightReach::operator()(const TriangleLight& l) const {
  if (l.two_sided) return all();
  return ray_half_space(origin, dir, l.p0, cross(l.p1 - l.p0, l.p2 - l.p0), tmin, tmax);
}

std::optional<RayRange> LightReach::operator()(const SphereLight&) const { return all(); }
std::optional<RayRange> LightReach::operator()(const DirectionalLight&) const { return all(); }
std::optional<RayRange> LightReach::operator()(const EnvironmentLight&) const { return all(); }

OrientedBox light_box(const BoxLight& light) {
  return {light.position,
          {cross(light.direction, light.up), light.up, light.direction},
          {-light.half_width, -light.half_height, 0.0f},
          {light.half_width, light.half_height, light.range}};
}

}  // namespace caligo
