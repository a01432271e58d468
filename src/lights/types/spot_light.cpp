// SpotLight: a point light limited to a cone with a smoothstep edge (pbrt-v4's falloff),
// with a range window, a gobo projected through the outer cone and an IES profile.
#include <cmath>

#include "core/ray_solids.h"
#include "lights/light_tree.h"
#include "lights/types/emitter_parts.h"

namespace caligo {

bool SpotLight::is_delta() const { return true; }

// The smoothstep falloff integrates to the cone midway (in cos theta) between inner and
// outer: exact, as smoothstep integrates to 1/2 over its ramp (light_test.cpp checks it). The
// IES profile's mean over the sphere stands for its mean over the cone (an approximation:
// powers only weight the choice of a light).
float SpotLight::power() const {
  return 2.0f * kPi * (1.0f - 0.5f * (cos_inner + cos_outer)) * intensity.average() * emitter::ies_mean(ies) *
         emitter::gobo_mean(gobo);
}

std::optional<Vec3> SpotLight::centre() const { return position; }

void SpotLight::pose(const LightPose& at) { emitter::pose_aimed(*this, at); }

std::optional<LightSample> SpotLight::sample(Vec3 receiver, Vec2) const {
  return emitter::from_arrival(delta_arrival(*this, receiver));
}

float SpotLight::pdf(Vec3, Vec3, Vec3, Vec3) const { return 0.0f; }
RGB SpotLight::escaped(Vec3) const { return RGB(0.0f); }

// One nappe of its outer cone (the smoothstep is 0 outside), cut by the range sphere when
// the range is finite.
std::optional<RayRange> SpotLight::reach(Vec3 origin, Vec3 dir, float tmin, float tmax) const {
  const auto cone = ray_cone(origin, dir, position, direction, cos_outer, tmin, tmax);
  return std::isfinite(range) ? overlap(cone, emitter::within_range(origin, dir, position, range, tmin, tmax))
                              : cone;
}

std::optional<LightBounds> SpotLight::bounds() const {
  return bounds_at_point(position, power(), direction, 1.0f, cos_outer);
}

std::optional<LightGeometry> SpotLight::surface() const { return std::nullopt; }

}  // namespace caligo
