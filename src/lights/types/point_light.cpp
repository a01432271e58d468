// PointLight: intensity in W/sr from a point, windowed by its range and shaped by an IES
// profile (lights/light_profile.h).
#include <cmath>

#include "lights/light_tree.h"
#include "lights/types/emitter_parts.h"

namespace caligo {

bool PointLight::is_delta() const { return true; }

float PointLight::power() const { return 4.0f * kPi * intensity.average() * emitter::ies_mean(ies); }

std::optional<Vec3> PointLight::centre() const { return position; }

void PointLight::pose(const LightPose& at) {
  if (at.position) position = *at.position;
}

std::optional<LightSample> PointLight::sample(Vec3 receiver, Vec2) const {
  return emitter::from_arrival(delta_arrival(*this, receiver));
}

float PointLight::pdf(Vec3, Vec3, Vec3, Vec3) const { return 0.0f; }
RGB PointLight::escaped(Vec3) const { return RGB(0.0f); }

// Its range sphere (the windowed falloff is 0 beyond), else everything.
std::optional<RayRange> PointLight::reach(Vec3 origin, Vec3 dir, float tmin, float tmax) const {
  return emitter::within_range(origin, dir, position, range, tmin, tmax);
}

std::optional<LightBounds> PointLight::bounds() const {
  return bounds_at_point(position, power(), {0, 0, 1}, -1.0f, kCosHemisphere);
}

std::optional<LightGeometry> PointLight::surface() const { return std::nullopt; }

}  // namespace caligo
