#include "lights/light_reach.h"

#include <cmath>

namespace caligo {
namespace {

struct Reach {
  Vec3 o, d;
  float tmin, tmax;

  std::optional<RayRange> all() const { return clip_range(tmin, tmax, tmin, tmax); }
  std::optional<RayRange> range(Vec3 centre, float r) const {
    return std::isfinite(r) ? ray_ball(o, d, centre, r, tmin, tmax) : all();
  }
  std::optional<RayRange> operator()(const PointLight& l) const { return range(l.position, l.range); }
  std::optional<RayRange> operator()(const SpotLight& l) const {
    const auto cone = ray_cone(o, d, l.position, l.direction, l.cos_outer, tmin, tmax);
    return std::isfinite(l.range) ? overlap(cone, range(l.position, l.range)) : cone;
  }
  std::optional<RayRange> operator()(const BoxLight& l) const { return ray_oriented_box(o, d, light_box(l), tmin, tmax); }
  std::optional<RayRange> operator()(const QuadLight& l) const {
    if (l.two_sided) return all();
    return ray_half_space(o, d, l.corner, cross(l.edge1, l.edge2), tmin, tmax);
  }
  std::optional<RayRange> operator()(const TriangleLight& l) const {
    if (l.two_sided) return all();
    return ray_half_space(o, d, l.p0, cross(l.p1 - l.p0, l.p2 - l.p0), tmin, tmax);
  }
  std::optional<RayRange> operator()(const SphereLight&) const { return all(); }
  std::optional<RayRange> operator()(const DirectionalLight&) const { return all(); }
  std::optional<RayRange> operator()(const EnvironmentLight&) const { return all(); }
};

}  // namespace

OrientedBox light_box(const BoxLight& light) {
  return {light.position,
          {cross(light.direction, light.up), light.up, light.direction},
          {-light.half_width, -light.half_height, 0.0f},
          {light.half_width, light.half_height, light.range}};
}

std::optional<RayRange> light_reach(const Light& light, Vec3 origin, Vec3 dir, float tmin, float tmax) {
  return std::visit(Reach{origin, dir, tmin, tmax}, light);
}

}  // namespace caligo
