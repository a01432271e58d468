// DiskLight: a flat disk of uniform radiance (Cycles' and Arnold's disk light), as a regular
// polygon: a sector chosen uniformly, then a point uniformly in its triangle, so the sampled
// area is exactly the visible surface's.
#include <algorithm>
#include <cmath>

#include "core/ray_solids.h"
#include "core/sampling.h"
#include "lights/light_tree.h"
#include "lights/types/emitter_parts.h"

namespace caligo {

float DiskLight::area() const { return 0.5f * float(kSides) * sqr(radius) * std::sin(2.0f * kPi / float(kSides)); }

Vec3 DiskLight::vertex(int k) const {
  const Frame frame = Frame::from_z(normal);
  const float phi = 2.0f * kPi * float(k % kSides) / float(kSides);
  return center + (frame.s * std::cos(phi) + frame.t * std::sin(phi)) * radius;
}

bool DiskLight::is_delta() const { return false; }

float DiskLight::power() const { return (two_sided ? 2.0f : 1.0f) * kPi * area() * radiance.average(); }

std::optional<Vec3> DiskLight::centre() const { return center; }

void DiskLight::pose(const LightPose&) {}

std::optional<LightSample> DiskLight::sample(Vec3 receiver, Vec2 u) const {
  const float scaled = u.x * float(kSides);
  const int k = std::min(int(scaled), kSides - 1);
  const Vec3 b = sample_uniform_triangle({scaled - float(k), u.y});
  const Vec3 p = center * b.x + vertex(k) * b.y + vertex(k + 1) * b.z;
  return emitter::area_point(receiver, p, normal, area(), emitter::one_sided(radiance, two_sided, normal, receiver - p));
}

float DiskLight::pdf(Vec3 receiver, Vec3, Vec3 on_light, Vec3 light_normal) const {
  return emitter::area_to_solid_angle(1.0f / area(), receiver, on_light, light_normal);
}

RGB DiskLight::escaped(Vec3) const { return RGB(0.0f); }

// The open half-space in front of the disk, unless two-sided.
std::optional<RayRange> DiskLight::reach(Vec3 origin, Vec3 dir, float tmin, float tmax) const {
  if (two_sided) return emitter::whole(tmin, tmax);
  return ray_half_space(origin, dir, center, normal, tmin, tmax);
}

// The square about the circle, in the disk's plane.
std::optional<LightBounds> DiskLight::bounds() const {
  const Frame frame = Frame::from_z(normal);
  const Vec3 s = frame.s * radius, t = frame.t * radius;
  return bounds_of_flat({center - s - t, center + s - t, center - s + t, center + s + t}, normal, two_sided, power());
}

// A fan about the centre, wound so that cross(p1 - p0, p2 - p0) is `normal`.
std::optional<LightGeometry> DiskLight::surface() const {
  VisibleTriangles fan;
  fan.positions.push_back(center);
  for (int k = 0; k < kSides; ++k) fan.positions.push_back(vertex(k));
  for (uint32_t k = 0; k < uint32_t(kSides); ++k) fan.indices.insert(fan.indices.end(), {0, k + 1, (k + 1) % kSides + 1});
  return LightGeometry{radiance, two_sided, std::move(fan)};
}

}  // namespace caligo
