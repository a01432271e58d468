// QuadLight: a parallelogram of uniform radiance, sampled by the solid angle it subtends
// (lights/area_light_sampling.h) where that is well conditioned, else by area.
#include "core/ray_solids.h"
#include "lights/area_light_sampling.h"
#include "lights/light_tree.h"
#include "lights/types/emitter_parts.h"

namespace caligo {

bool QuadLight::is_delta() const { return false; }

float QuadLight::power() const {
  return (two_sided ? 2.0f : 1.0f) * kPi * length(cross(edge1, edge2)) * radiance.average();
}

std::optional<Vec3> QuadLight::centre() const { return corner + (edge1 + edge2) * 0.5f; }

void QuadLight::pose(const LightPose&) {}

std::optional<LightSample> QuadLight::sample(Vec3 receiver, Vec2 u) const {
  if (const SolidAngleSampling s = solid_angle_sampling(*this, receiver); s.solid_angle > 0.0)
    return emitter::solid_angle_point(receiver, sample_solid_angle(s, u), s.solid_angle, radiance);
  const Vec3 p = corner + edge1 * u.x + edge2 * u.y;
  const Vec3 c = cross(edge1, edge2);
  const float area = length(c);
  const Vec3 n = c / area;
  return emitter::area_point(receiver, p, n, area, emitter::one_sided(radiance, two_sided, n, receiver - p));
}

float QuadLight::pdf(Vec3 receiver, Vec3, Vec3 on_light, Vec3 light_normal) const {
  if (const double omega = solid_angle_sampling(*this, receiver).solid_angle; omega > 0.0) return float(1.0 / omega);
  return emitter::area_to_solid_angle(1.0f / length(cross(edge1, edge2)), receiver, on_light, light_normal);
}

RGB QuadLight::escaped(Vec3) const { return RGB(0.0f); }

// The open half-space in front of the emitting face, unless two-sided.
std::optional<RayRange> QuadLight::reach(Vec3 origin, Vec3 dir, float tmin, float tmax) const {
  if (two_sided) return emitter::whole(tmin, tmax);
  return ray_half_space(origin, dir, corner, cross(edge1, edge2), tmin, tmax);
}

std::optional<LightBounds> QuadLight::bounds() const {
  return bounds_of_flat({corner, corner + edge1, corner + edge2, corner + edge1 + edge2}, cross(edge1, edge2),
                        two_sided, power());
}

std::optional<LightGeometry> QuadLight::surface() const {
  return LightGeometry{
      radiance, two_sided,
      VisibleTriangles{{corner, corner + edge1, corner + edge1 + edge2, corner + edge2}, {0, 1, 2, 0, 2, 3}}};
}

}  // namespace caligo
