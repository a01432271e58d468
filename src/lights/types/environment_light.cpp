// EnvironmentLight: radiance from every direction, constant or an importance-sampled
// lat-long map (lights/environment_map.h) turned about +Y.
#include "core/sampling.h"
#include "lights/environment_map.h"
#include "lights/light_tree.h"
#include "lights/types/emitter_parts.h"

namespace caligo {
namespace {

// The map's frame from the world's and back: R_y(-angle) and R_y(angle).
Vec3 to_map(const EnvironmentLight& l, Vec3 w) {
  return {l.cos_rotation * w.x - l.sin_rotation * w.z, w.y, l.sin_rotation * w.x + l.cos_rotation * w.z};
}
Vec3 to_world(const EnvironmentLight& l, Vec3 m) {
  return {l.cos_rotation * m.x + l.sin_rotation * m.z, m.y, -l.sin_rotation * m.x + l.cos_rotation * m.z};
}

}  // namespace

bool EnvironmentLight::is_delta() const { return false; }

// pi r^2 times the radiance integrated over the sphere (4 pi L for a constant one).
float EnvironmentLight::power() const {
  const RGB integral = map ? radiance * map->integral() : radiance * (4.0f * kPi);
  return kPi * sqr(scene_radius) * integral.average();
}

std::optional<Vec3> EnvironmentLight::centre() const { return std::nullopt; }

void EnvironmentLight::pose(const LightPose&) {}

// A constant environment uniformly over the sphere; a map by its own distribution.
std::optional<LightSample> EnvironmentLight::sample(Vec3, Vec2 u) const {
  if (!map) return LightSample{radiance, sample_uniform_sphere(u), kInfinity, uniform_sphere_pdf(), false};
  const auto s = map->sample(u);
  if (!s) return std::nullopt;
  return LightSample{radiance * map->lookup(s->w), to_world(*this, s->w), kInfinity, s->pdf, false};
}

float EnvironmentLight::pdf(Vec3, Vec3 wi, Vec3, Vec3) const {
  return map ? map->pdf(to_map(*this, wi)) : uniform_sphere_pdf();
}

RGB EnvironmentLight::escaped(Vec3 w) const { return map ? radiance * map->lookup(to_map(*this, w)) : radiance; }

std::optional<RayRange> EnvironmentLight::reach(Vec3, Vec3, float tmin, float tmax) const {
  return emitter::whole(tmin, tmax);
}

std::optional<LightBounds> EnvironmentLight::bounds() const { return std::nullopt; }
std::optional<LightGeometry> EnvironmentLight::surface() const { return std::nullopt; }

}  // namespace caligo
