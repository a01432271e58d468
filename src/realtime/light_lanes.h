// A shaded light prepared for 8-lane arrival: the one SIMD form of lights/light_profile.h's
// delta_arrival (cone, range window, gobo, IES) that the accumulation march and the surface
// shading both call. Built once per light and frame; read-only afterwards (thread-safe). Its
// lanes agree with the scalar delta_arrival to float rounding (accumulate_test.cpp,
// surface_shading_test.cpp).
#pragma once

#include <xsimd/xsimd.hpp>

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

}  // namespace caligo
