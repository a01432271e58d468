// DirectionalLight: light from a distant disk (the sun) of an angular radius, or a delta
// direction at radius 0. At infinity: it lights everything, and rays leaving the scene
// inside its disk see it.
#include "core/sampling.h"
#include "lights/light_tree.h"
#include "lights/types/emitter_parts.h"

namespace caligo {
namespace {

// A sun of irradiance E and angular radius a has uniform radiance E / (pi sin^2 a) over its
// disk: the cosine-weighted solid angle of a cone of half-angle a is pi sin^2 a.
RGB sun_radiance(const DirectionalLight& l) {
  const float sin2 = 1.0f - sqr(l.cos_angular_radius);
  return l.irradiance / (kPi * sin2);
}

}  // namespace

bool DirectionalLight::is_delta() const { return cos_angular_radius >= 1.0f; }

float DirectionalLight::power() const { return kPi * sqr(scene_radius) * irradiance.average(); }

// Parallel light does not peak near a point: density sampling serves it.
std::optional<Vec3> DirectionalLight::centre() const { return std::nullopt; }

void DirectionalLight::pose(const LightPose& at) {
  if (at.direction) direction = *at.direction;
}

std::optional<LightSample> DirectionalLight::sample(Vec3, Vec2 u) const {
  const Vec3 towards = -direction;
  if (cos_angular_radius >= 1.0f) return LightSample{irradiance, towards, kInfinity, 1.0f, true};
  const Vec3 wi = Frame::from_z(towards).to_world(sample_uniform_cone(u, cos_angular_radius));
  return LightSample{escaped(wi), wi, kInfinity, uniform_cone_pdf(cos_angular_radius), false};
}

float DirectionalLight::pdf(Vec3, Vec3 wi, Vec3, Vec3) const {
  if (cos_angular_radius >= 1.0f || dot(-direction, wi) < cos_angular_radius) return 0.0f;
  return uniform_cone_pdf(cos_angular_radius);
}

// A delta sun cannot be hit.
RGB DirectionalLight::escaped(Vec3 w) const {
  if (cos_angular_radius >= 1.0f || dot(-direction, w) < cos_angular_radius) return RGB(0.0f);
  return sun_radiance(*this);
}

std::optional<RayRange> DirectionalLight::reach(Vec3, Vec3, float tmin, float tmax) const {
  return emitter::whole(tmin, tmax);
}

std::optional<LightBounds> DirectionalLight::bounds() const { return std::nullopt; }
std::optional<LightGeometry> DirectionalLight::surface() const { return std::nullopt; }

}  // namespace caligo
