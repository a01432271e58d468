// Internal to surface_shading.cpp and surface_shading_simd.cpp: the scalar per-pixel
// shading (the reference, and the fallback for lanes the SIMD path does not handle) and the
// 8-wide row loop.
#pragma once

#include <span>

#include "realtime/surface_shading.h"
#include "scene/scene.h"

namespace caligo::shading {

struct ShadeContext {
  const GBuffer& g;
  const View& camera;
  const Scene& scene;
  std::span<const FrameLight> lights;
  float far;  // a distance that leaves every surface and volume (directional lights)
  bool simd;
};

RGB transmittance(const VolumeScene& volumes, Vec3 a, Vec3 b);
// One light's reflected radiance at a diffuse point p with unit normal n, f = albedo / pi.
RGB light_term(const ShadeContext& c, const FrameLight& light, Vec3 p, Vec3 n, RGB f);
// The whole pixel: emission plus the active lights, times the camera ray's transmittance.
RGB shade_pixel(const ShadeContext& c, size_t pixel, Vec3 p, Vec3 eye, std::span<const int> active);
// Shades pixels [x0, x) of row y 8 at a time and returns x (<= x1); the caller shades the rest.
int shade_row_simd(const ShadeContext& c, int y, int x0, int x1, std::span<const int> active,
                   ColorPlanes& out);

}  // namespace caligo::shading
