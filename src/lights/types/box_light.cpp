// BoxLight: parallel light filling an oriented box (the seed's "box light"), with a gobo
// over its emitting face. Bounded, so not at infinity: no escaped radiance, finite shadow rays.
#include "lights/light_reach.h"
#include "lights/light_tree.h"
#include "lights/types/emitter_parts.h"

namespace caligo {

bool BoxLight::is_delta() const { return true; }

// Irradiance times the emitting face's area.
float BoxLight::power() const {
  return 4.0f * half_width * half_height * irradiance.average() * emitter::gobo_mean(gobo);
}

// Parallel light does not peak near a point: density sampling serves it.
std::optional<Vec3> BoxLight::centre() const { return std::nullopt; }

void BoxLight::pose(const LightPose& at) { emitter::pose_aimed(*this, at); }

// The shadow ray ends on the emitting face (distance = depth inside the box).
std::optional<LightSample> BoxLight::sample(Vec3 receiver, Vec2) const {
  return emitter::from_arrival(delta_arrival(*this, receiver));
}

float BoxLight::pdf(Vec3, Vec3, Vec3, Vec3) const { return 0.0f; }
RGB BoxLight::escaped(Vec3) const { return RGB(0.0f); }

std::optional<RayRange> BoxLight::reach(Vec3 origin, Vec3 dir, float tmin, float tmax) const {
  return ray_oriented_box(origin, dir, light_box(*this), tmin, tmax);
}

// The whole lit box, emitting along `direction`: every point it lights is in front of the face.
std::optional<LightBounds> BoxLight::bounds() const {
  const Vec3 right = cross(direction, up) * half_width, face_up = up * half_height;
  LightBounds b = bounds_at_point(position, power(), direction, 1.0f, kCosHemisphere);
  for (float s : {-1.0f, 1.0f})
    for (float t : {-1.0f, 1.0f}) {
      b.box.extend(position + right * s + face_up * t);
      b.box.extend(position + right * s + face_up * t + direction * range);
    }
  return b;
}

std::optional<LightGeometry> BoxLight::surface() const { return std::nullopt; }

}  // namespace caligo
