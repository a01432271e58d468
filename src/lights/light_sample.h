// Sampling lights from a receiving point (next-event estimation) and the matching pdfs
// for multiple importance sampling with BSDF-sampled rays.
//
// All pdfs are with respect to solid angle at the receiving point; delta lights report
// pdf 1 and delta = true (their radiance field already holds the 1/r^2).
#pragma once

#include <optional>

#include "core/vec.h"
#include "lights/light.h"

namespace caligo {

struct LightSample {
  RGB radiance;    // arriving at the receiver along -wi (already / r^2 for point and spot)
  Vec3 wi;         // unit direction from the receiver towards the light
  float distance;  // to the sampled point; kInfinity for lights at infinity
  float pdf;       // solid angle; 1 for delta lights
  bool delta = false;
};

// std::nullopt when the sample carries no light (behind a one-sided emitter, outside a spot cone).
std::optional<LightSample> sample_light(const Light& light, Vec3 receiver, Vec2 u);

// The solid-angle pdf with which sample_light would have chosen the point `on_light` (with
// unit normal `light_normal`) from `receiver`. For lights at infinity pass the direction in
// `wi` and ignore the rest. Zero for delta lights.
float light_pdf(const Light& light, Vec3 receiver, Vec3 wi, Vec3 on_light, Vec3 light_normal);

// Radiance a ray leaving the scene in direction `w` receives from a light at infinity.
RGB escaped_radiance(const Light& light, Vec3 w);

}  // namespace caligo
