// TriangleLight: one triangle of a shape with an emissive material. The shape itself is the
// visible geometry (the scene builds it), so the light shows none of its own.
#include "core/sampling.h"
#include "core/ray_solids.h"
#include "lights/area_light_sampling.h"
#include "lights/light_tree.h"
#include "lights/types/emitter_parts.h"

namespace caligo {

bool TriangleLight::is_delta() const { return false; }

float TriangleLight::power() const {
  return (two_sided ? 2.0f : 1.0f) * kPi * 0.5f * length(cross(p1 - p0, p2 - p0)) * radiance.average();
}

std::optional<Vec3> TriangleLight::centre() const { return (p0 + p1 + p2) / 3.0f; }

void TriangleLight::pose(const LightPose&) {}

std::optional<LightSample> TriangleLight::sample(Vec3 receiver, Vec2 u) const {
  if (const SolidAngleSampling s = solid_angle_sampling(*this, receiver); s.solid_angle > 0.0)
    return emitter::solid_angle_point(receiver, sample_solid_angle(s, u), s.solid_angle, radiance);
  const Vec3 b = sample_uniform_triangle(u);
  const Vec3 p = p0 * b.x + p1 * b.y + p2 * b.z;
  const Vec3 c = cross(p1 - p0, p2 - p0);
  const float area = 0.5f * length(c);
  const Vec3 n = normalize(c);
  return emitter::area_point(receiver, p, n, area, emitter::one_sided(radiance, two_sided, n, receiver - p));
}

float TriangleLight::pdf(Vec3 receiver, Vec3, Vec3 on_light, Vec3 light_normal) const {
  if (const double omega = solid_angle_sampling(*this, receiver).solid_angle; omega > 0.0) return float(1.0 / omega);
  return emitter::area_to_solid_angle(1.0f / (0.5f * length(cross(p1 - p0, p2 - p0))), receiver, on_light,
                                      light_normal);
}

RGB TriangleLight::escaped(Vec3) const { return RGB(0.0f); }

// The open half-space in front of the emitting face, unless two-sided.
std::optional<RayRange> TriangleLight::reach(Vec3 origin, Vec3 dir, float tmin, float tmax) const {
  if (two_sided) return emitter::whole(tmin, tmax);
  return ray_half_space(origin, dir, p0, cross(p1 - p0, p2 - p0), tmin, tmax);
}

std::optional<LightBounds> TriangleLight::bounds() const {
  return bounds_of_flat({p0, p1, p2}, cross(p1 - p0, p2 - p0), two_sided, power());
}

std::optional<LightGeometry> TriangleLight::surface() const { return std::nullopt; }

}  // namespace caligo
