// Internal to surface_shading.cpp and surface_shading_simd.cpp: the scalar per-pixel
// shading (the reference) and the 8-wide path with its once-per-frame set-up.
#pragma once

#include <memory>
#include <optional>
#include <span>

#include "core/bounds.h"
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

// May the spot light's outer cone (where spot_cone is non-zero) meet the box? Conservative
// (tile culling); cones of 90 degrees or wider always may.
bool spot_cone_may_reach(const SpotLight& light, const Bounds3& box);
RGB transmittance(const VolumeScene& volumes, Vec3 a, Vec3 b);
// Far enough along any direction to leave every surface and volume from inside them.
float escape_distance(const Scene& scene);
// What the real-time passes shade a material's surface with: f = albedo / pi of a diffuse BSDF,
// or nothing (emission only) for the others, which they cannot shade: glass, black and null
// surfaces. A visit, so a new BSDF does not compile until it is decided here.
std::optional<RGB> diffuse_f(const Bsdf& bsdf);
// One light's reflected radiance at a diffuse point p with unit normal n, f = albedo / pi.
RGB light_term(const ShadeContext& c, const FrameLight& light, Vec3 p, Vec3 n, RGB f);
// The whole pixel: emission plus the active lights, times the camera ray's transmittance.
RGB shade_pixel(const ShadeContext& c, size_t pixel, Vec3 p, Vec3 eye, std::span<const int> active);

// What the 8-wide path derives once per frame: material tables, per-light constants (gobo
// rotation, frames), the media in object space. Defined in surface_shading_simd.cpp.
struct SimdFrame;
struct SimdFrameDeleter {
  void operator()(SimdFrame* f) const;
};
using SimdFramePtr = std::unique_ptr<SimdFrame, SimdFrameDeleter>;
SimdFramePtr prepare_simd(const ShadeContext& c);

// Bounds of the surface points of rows [y0, y1), columns [x0, x1) (x1 - x0 a multiple of 8),
// reconstructed exactly as shade_row_simd reconstructs them; sky pixels are left out.
Bounds3 points_bounds_simd(const ShadeContext& c, int y0, int y1, int x0, int x1);
// Shades pixels [x0, x1) x [y0, y1) 8 at a time (x1 - x0 a multiple of 8) with the lights
// `active`; `bounds` holds every surface point of the tile they belong to.
void shade_rect_simd(const ShadeContext& c, const SimdFrame& f, int y0, int y1, int x0, int x1,
                     std::span<const int> active, const Bounds3& bounds, ColorPlanes& out);

}  // namespace caligo::shading
