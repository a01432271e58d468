// The shape of a delta light's emission: cone, range window, gobo and IES profile. One set
// of functions shared by the path tracer (sample_light) and the real-time passes (their
// scalar path calls these; the SIMD path is tested against it), so the reference and the
// real-time frame see identical light.
#pragma once

#include <optional>

#include "core/rgb.h"
#include "core/vec.h"
#include "lights/light.h"

namespace caligo {

// The light arriving at a point from a delta light: radiance along -wi already divided by
// distance^2 (point, spot) and scaled by cone, range window, gobo and IES.
struct DeltaArrival {
  RGB radiance;
  Vec3 wi;         // unit, from the receiver towards the light
  float distance;  // to the light (box light: to its emitting face)
};

// (1 - (d / range)^4)^2 for d < range, else 0; 1 for an infinite range.
float range_window(float distance, float range);
// Smoothstep cone falloff for a unit direction leaving the light.
float spot_cone(const SpotLight& light, Vec3 w_from_light);
// The gobo's colour at face/projection coordinates uv (before its rotation and offset);
// white when the gobo has no image.
RGB gobo_filter(const Gobo& gobo, Vec2 uv);
// Where a direction leaving a spot light lands on its gobo: the outer cone's square
// tan-plane mapped to [0,1]^2 (u along right = cross(direction, up), v along up).
Vec2 spot_gobo_uv(const SpotLight& light, Vec3 w_from_light);
// The profile's relative intensity (max 1) in a unit direction leaving the light; 1 without one.
float ies_factor(const IesAttachment& ies, Vec3 w_from_light);

std::optional<DeltaArrival> delta_arrival(const PointLight& light, Vec3 receiver);
std::optional<DeltaArrival> delta_arrival(const SpotLight& light, Vec3 receiver);
// std::nullopt outside the box.
std::optional<DeltaArrival> delta_arrival(const BoxLight& light, Vec3 receiver);
// Parallel light from everywhere: its irradiance along -direction, at infinite distance.
inline std::optional<DeltaArrival> delta_arrival(const DirectionalLight& light, Vec3) {
  return DeltaArrival{light.irradiance, -light.direction, kInfinity};
}

}  // namespace caligo
