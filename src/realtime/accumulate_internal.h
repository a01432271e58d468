// Pieces of accumulate_light shared by its scalar (accumulate.cpp) and SIMD
// (accumulate_simd.cpp) marches: the per-pixel setup and the light's point of emission.
// Internal to src/realtime; tests use it to compare the two marches pixel by pixel.
#pragma once

#include <cmath>
#include <memory>
#include <span>
#include <vector>

#include "core/rgb.h"
#include "core/vec.h"
#include "realtime/frame_light.h"
#include "realtime/accumulation_rays.h"
#include "realtime/light_volume.h"
#include "realtime/passes.h"
#include "volumes/volume_scene.h"

namespace caligo {

// One pixel's march: sample k sits at t0 + (k + offset) * step along origin + t dir.
struct PixelMarch {
  Vec3 origin, dir;  // dir unit
  float t0 = 0.0f, step = 0.0f, offset = 0.5f;
  int samples = 0;
  std::span<const VolumeInterval> intervals;  // the volume primitives on the ray
  // Equiangular placement (point and spot lights, Kulla & Fajardo 2012): the steps are
  // uniform in the angle theta under which the light sees the ray, t = tc + D tan(theta),
  // each weighted by dt/dtheta x dtheta = (D^2 + (t - tc)^2) / D x dtheta, which cancels the
  // 1/d^2 of the light. Uniform steps miss the peak of a ray passing near the light.
  bool equiangular = false;
  float tc = 0.0f, D = 0.0f, theta0 = 0.0f, dtheta = 0.0f;
};

// Where sample k (plus the pixel's offset) lies on the ray, and its quadrature weight.
inline float march_sample(const PixelMarch& m, float k, float& weight) {
  if (!m.equiangular) {
    weight = m.step;
    return m.t0 + (k + m.offset) * m.step;
  }
  const float x = m.D * std::tan(m.theta0 + (k + m.offset) * m.dtheta);
  weight = m.dtheta * (m.D * m.D + x * x) / m.D;
  return m.tc + x;
}

// The march of one pixel's ray given the light volume's span of it (light_volume_interval over
// [0, t_end]), or false when the span, the depth and the media leave nothing to march.
// `focus`: the point light or spot apex the steps crowd towards (null: uniform steps).
bool setup_pixel_march(RayRange span, const AccumulationRays::PixelRay& ray,
                       std::span<const VolumeInterval> intervals, const AccumulationSettings& settings,
                       PixelMarch& march, const Vec3* focus = nullptr);
// The point equiangular placement aims at: point lights and spot apexes; null otherwise.
const Vec3* equiangular_focus(const ShadedLight& light);

// Distance beyond which no medium lies from any point inside one (directional lights'
// transmittance segments end there).
float media_extent(const VolumeScene& volumes);

// In-scattered radiance of one pixel, before volumetric_intensity (the reference path:
// light_profile.h's delta_arrival, media.h's optical depths, ShadowMap::visibility).
RGB march_scalar(const FrameLight& light, const VolumeScene& volumes, const PixelMarch& march,
                 float multiple_scattering_floor, float far);
// The integrand of march_scalar at t without the camera's transmittance: radiance scattered
// towards -march.dir per unit length (SimdMarcher::inscatter's reference).
RGB inscatter_scalar(const FrameLight& light, const VolumeScene& volumes, const PixelMarch& march, float t,
                     float multiple_scattering_floor, float far);

// The same with xsimd, 8 samples at a time. Built once per light and frame.
class SimdMarcher {
 public:
  SimdMarcher(const FrameLight& light, const VolumeScene& volumes, float multiple_scattering_floor,
              float far);
  ~SimdMarcher();
  // False when the light or the media need the scalar path (radial-falloff density fields,
  // area lights); march() then must not be called.
  bool supported() const { return supported_; }
  RGB march(const PixelMarch& march) const;
  // Adds to out[i] the radiance scattered towards -march.dir at march.origin + t[i] march.dir,
  // per unit length and without the camera's transmittance (the froxel grid's injection);
  // march.intervals must hold the media on the ray up to the last t.
  void inscatter(const PixelMarch& march, std::span<const float> t, RGB* out) const;
  // Cache hints for the shadow-map texels march() will read: issued a pixel ahead, so the
  // scattered texel loads (the march's main cost when a map outgrows the cache) overlap
  // the previous pixel's arithmetic instead of stalling it.
  void prefetch(const PixelMarch& march) const;

  struct Data;

 private:
  std::unique_ptr<Data> data_;
  bool supported_ = false;
};

}  // namespace caligo
