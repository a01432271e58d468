// SphereLight: a spherical emitter of uniform radiance, sampled by the cone it subtends
// (uniform area sampling from inside), visible to camera and bounce rays.
#include <cmath>

#include "core/sampling.h"
#include "lights/light_tree.h"
#include "lights/types/emitter_parts.h"

namespace caligo {

bool SphereLight::is_delta() const { return false; }

float SphereLight::power() const {
  return (two_sided ? 2.0f : 1.0f) * kPi * 4.0f * kPi * sqr(radius) * radiance.average();
}

std::optional<Vec3> SphereLight::centre() const { return center; }

void SphereLight::pose(const LightPose&) {}

std::optional<LightSample> SphereLight::sample(Vec3 receiver, Vec2 u) const {
  const Vec3 to_center = center - receiver;
  const float dist2 = length_squared(to_center);
  const float r2 = sqr(radius);
  if (dist2 <= r2 * 1.0001f) {
    const Vec3 n = sample_uniform_sphere(u);
    const Vec3 p = center + n * radius;
    return emitter::area_point(receiver, p, n, 4.0f * kPi * r2,
                               emitter::one_sided(radiance, two_sided, n, receiver - p));
  }
  const float dist = std::sqrt(dist2);
  const float sin2_max = r2 / dist2;
  const float cos_max = safe_sqrt(1.0f - sin2_max);
  if (radiance.is_black()) return std::nullopt;
  const Frame frame = Frame::from_z(to_center / dist);
  const Vec3 wi = frame.to_world(sample_uniform_cone(u, cos_max));
  // Distance to the near intersection of the sampled direction with the sphere.
  const float b = dot(wi, to_center);
  const float t = b - safe_sqrt(r2 - (dist2 - b * b));
  return LightSample{radiance, wi, t, uniform_cone_pdf(cos_max), false};
}

float SphereLight::pdf(Vec3 receiver, Vec3, Vec3 on_light, Vec3 light_normal) const {
  const float dist2 = length_squared(center - receiver);
  const float r2 = sqr(radius);
  if (dist2 <= r2 * 1.0001f)
    return emitter::area_to_solid_angle(1.0f / (4.0f * kPi * r2), receiver, on_light, light_normal);
  return uniform_cone_pdf(safe_sqrt(1.0f - r2 / dist2));
}

RGB SphereLight::escaped(Vec3) const { return RGB(0.0f); }

// Emits in every direction (inwards too when two-sided): the whole segment.
std::optional<RayRange> SphereLight::reach(Vec3, Vec3, float tmin, float tmax) const {
  return emitter::whole(tmin, tmax);
}

std::optional<LightBounds> SphereLight::bounds() const {
  LightBounds b = bounds_at_point(center - Vec3(radius), power(), {0, 0, 1}, -1.0f, kCosHemisphere);
  b.box.extend(center + Vec3(radius));
  return b;
}

std::optional<LightGeometry> SphereLight::surface() const {
  return LightGeometry{radiance, two_sided, VisibleSphere{center, radius}};
}

}  // namespace caligo
