// A shaded light prepared for 8-lane arrival: the one SIMD form of lights/light_profile.h's
// delta_arrival (cone, range window, gobo, IES) that the accumulation march and the surface
// shading both call. Built once per light and frame; read-only afterwards (thread-safe). Its
// lanes agree with the scalar delta_arrival to float rounding (accumulate_test.cpp,
// surface_shading_test.cpp).
#pragma once

#include <xsimd/xsimd.hpp>

#include <cmath>
#include <optional>

#include "realtime/frame_light.h"
#include "realtime/light_profile_simd.h"

namespace caligo {

class LightLanes {
 public:
  using Batch = xsimd::batch<float>;
  using Mask = xsimd::batch_bool<float>;

  explicit LightLanes(const ShadedLight& light);

  // The light at the lanes' points (px, py, pz): radiance along -wi (point and spot lights:
  // already / distance^2) or irradiance, the unit direction towards the light, the distance to
  // it (box lights: to the emitting face; directional: infinity), and where it arrives at all.
  struct Arrival {
    Batch r, g, b;
    Batch wx, wy, wz;
    Batch distance;
    Mask mask;
  };
  Arrival at(const Batch& px, const Batch& py, const Batch& pz) const;

  // Light from one direction everywhere (box, directional): -direction() at every point.
  bool parallel() const { return kind_ == Kind::box || kind_ == Kind::directional; }
  Vec3 position() const { return position_; }    // point and spot lights
  Vec3 direction() const { return direction_; }  // spot axis, box and directional travel

 private:
  enum class Kind { point, spot, box, directional };
  Kind kind_ = Kind::point;
  Vec3 position_, direction_, up_, right_;
  float cos_inner_ = 1.0f, cos_outer_ = 0.0f, range_ = kInfinity, inv_range_ = 0.0f;
  float half_width_ = 0.0f, half_height_ = 0.0f;
  RGB color_;
  std::optional<SpotGoboSampler> spot_gobo_;
  std::optional<GoboSampler> box_gobo_;
  std::optional<IesSampler> ies_;

  Arrival point_like(const Batch& px, const Batch& py, const Batch& pz) const;
  Arrival box(const Batch& px, const Batch& py, const Batch& pz) const;
};

// Defined here, not in light_lanes.cpp: the accumulation march calls at() for every 8 samples
// of every pixel, and across translation units it would not inline.
namespace light_lanes_detail {

using B = xsimd::batch<float>;

// light_profile.cpp's range_window: (1 - (d / range)^4)^2 inside the range.
inline B range_window(const B& dist, float range, float inv_range) {
  if (!std::isfinite(range)) return B(1.0f);
  const B x = dist * inv_range;
  const B x2 = x * x;
  const B w = 1.0f - x2 * x2;
  return xsimd::select(dist < range, w * w, B(0.0f));
}

// math.h's smoothstep; the edge width's reciprocal once per call: a multiply, not a division,
// per lane.
inline B smoothstep(float e0, float e1, const B& x) {
  if (e0 == e1) return xsimd::select(x < e0, B(0.0f), B(1.0f));
  const B t = xsimd::min(xsimd::max((x - e0) * (1.0f / (e1 - e0)), B(0.0f)), B(1.0f));
  return t * t * (3.0f - 2.0f * t);
}

}  // namespace light_lanes_detail

inline LightLanes::Arrival LightLanes::point_like(const Batch& px, const Batch& py, const Batch& pz) const {
  const Batch dx = position_.x - px, dy = position_.y - py, dz = position_.z - pz;
  const Batch dist2 = dx * dx + dy * dy + dz * dz;
  Arrival a;
  a.distance = xsimd::sqrt(dist2);
  const Batch inv = 1.0f / a.distance;
  a.wx = dx * inv, a.wy = dy * inv, a.wz = dz * inv;
  Batch scale = light_lanes_detail::range_window(a.distance, range_, inv_range_) * (inv * inv);
  const Batch ox = -a.wx, oy = -a.wy, oz = -a.wz;  // leaving the light
  if (kind_ == Kind::spot)
    scale *=
        light_lanes_detail::smoothstep(cos_outer_, cos_inner_, ox * direction_.x + oy * direction_.y + oz * direction_.z);
  scale = xsimd::select(dist2 > 0.0f, scale, Batch(0.0f));
  if (ies_ && xsimd::any(scale > 0.0f)) scale *= ies_->factor(ox, oy, oz);
  a.mask = scale > 0.0f;
  Batch r(color_.r), g(color_.g), b(color_.b);
  if (spot_gobo_ && xsimd::any(a.mask)) {
    const RgbBatch f = spot_gobo_->filter(ox, oy, oz);
    r *= f.r, g *= f.g, b *= f.b;
  }
  a.r = scale * r, a.g = scale * g, a.b = scale * b;
  return a;
}

inline LightLanes::Arrival LightLanes::box(const Batch& px, const Batch& py, const Batch& pz) const {
  const Batch lx = px - position_.x, ly = py - position_.y, lz = pz - position_.z;
  const Batch along = lx * direction_.x + ly * direction_.y + lz * direction_.z;
  const Batch x = lx * right_.x + ly * right_.y + lz * right_.z, y = lx * up_.x + ly * up_.y + lz * up_.z;
  Arrival a;
  a.mask = (along >= 0.0f) & (along <= range_) & (xsimd::abs(x) <= half_width_) & (xsimd::abs(y) <= half_height_);
  a.wx = Batch(-direction_.x), a.wy = Batch(-direction_.y), a.wz = Batch(-direction_.z);
  a.distance = along;
  const Batch scale = xsimd::select(a.mask, Batch(1.0f), Batch(0.0f));
  Batch r(color_.r), g(color_.g), b(color_.b);
  if (box_gobo_ && xsimd::any(a.mask)) {
    // delta_arrival's uv on the emitting face.
    const RgbBatch f = box_gobo_->filter(0.5f + 0.5f * x / half_width_, 0.5f + 0.5f * y / half_height_);
    r *= f.r, g *= f.g, b *= f.b;
  }
  a.r = scale * r, a.g = scale * g, a.b = scale * b;
  return a;
}

inline LightLanes::Arrival LightLanes::at(const Batch& px, const Batch& py, const Batch& pz) const {
  switch (kind_) {
    case Kind::point:
    case Kind::spot:
      return point_like(px, py, pz);
    case Kind::box:
      return box(px, py, pz);
    case Kind::directional:
      break;
  }
  return {Batch(color_.r),      Batch(color_.g),      Batch(color_.b),  Batch(-direction_.x),
          Batch(-direction_.y), Batch(-direction_.z), Batch(kInfinity), Mask(true)};
}

}  // namespace caligo
