#include "realtime/light_volume_simd.h"

#include <cmath>

#include "core/overloaded.h"
#include "lights/light_reach.h"

namespace caligo {

// The solid of each shaded light, as light_reach bounds it.
LightVolumeLanes::LightVolumeLanes(const ShadedLight& light) {
  const auto range = [](Vec3 centre, float r) -> std::optional<Ball> {
    return std::isfinite(r) ? std::optional<Ball>(Ball{centre, r}) : std::nullopt;
  };
  solid_ = std::visit(
      Overloaded{[&](const PointLight& l) -> decltype(solid_) {
                   if (const auto ball = range(l.position, l.range)) return *ball;
                   return Whole{};
                 },
                 [&](const SpotLight& l) -> decltype(solid_) {
                   const auto ball = range(l.position, l.range);
                   // Not convex past 90 degrees: the whole ray (then the range sphere), as ray_cone.
                   if (l.cos_outer <= 0.0f) return ball ? decltype(solid_)(*ball) : Whole{};
                   return Cone{l.position, l.direction, l.cos_outer * l.cos_outer, ball};
                 },
                 [](const BoxLight& l) -> decltype(solid_) { return light_box(l); },
                 [](const DirectionalLight&) -> decltype(solid_) { return Whole{}; }},
      light);
}

LightVolumeLanes::Result LightVolumeLanes::intervals(const lanes::Rays& rays) const {
  return std::visit(Overloaded{[&](const Whole&) { return lanes::whole(rays); },
                               [&](const Ball& b) { return lanes::ray_ball(rays, b.centre, b.radius); },
                               [&](const Cone& c) {
                                 const Result cone = lanes::ray_cone(rays, c.apex, c.axis, c.cos2);
                                 if (!c.range) return cone;
                                 return lanes::overlap(cone, lanes::ray_ball(rays, c.range->centre, c.range->radius));
                               },
                               [&](const OrientedBox& box) { return lanes::ray_oriented_box(rays, box); }},
                    solid_);
}

}  // namespace caligo
