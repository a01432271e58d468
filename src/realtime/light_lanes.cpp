#include "realtime/light_lanes.h"

#include <cmath>

#include "core/overloaded.h"

namespace caligo {
namespace {

using Batch = LightLanes::Batch;
using Mask = LightLanes::Mask;

// light_profile.cpp's range_window: (1 - (d / range)^4)^2 inside the range.
Batch range_window(const Batch& dist, float range, float inv_range) {
  if (!std::isfinite(range)) return Batch(1.0f);
  const Batch x = dist * inv_range;
  const Batch x2 = x * x;
  const Batch w = 1.0f - x2 * x2;
  return xsimd::select(dist < range, w * w, Batch(0.0f));
}

// math.h's smoothstep; the edge width's reciprocal once per call: a multiply, not a division,
// per lane.
Batch smoothstep(float e0, float e1, const Batch& x) {
  if (e0 == e1) return xsimd::select(x < e0, Batch(0.0f), Batch(1.0f));
  const Batch t = xsimd::min(xsimd::max((x - e0) * (1.0f / (e1 - e0)), Batch(0.0f)), Batch(1.0f));
  return t * t * (3.0f - 2.0f * t);
}

float inverse_range(float range) { return std::isfinite(range) ? 1.0f / range : 0.0f; }

}  // namespace

LightLanes::LightLanes(const ShadedLight& light) {
  std::visit(Overloaded{[&](const PointLight& l) {
                          kind_ = Kind::point;
                          position_ = l.position;
                          range_ = l.range;
                          color_ = l.intensity;
                          if (l.ies.profile) ies_.emplace(l.ies);
                        },
                        [&](const SpotLight& l) {
                          kind_ = Kind::spot;
                          position_ = l.position;
                          direction_ = l.direction;
                          cos_inner_ = l.cos_inner;
                          cos_outer_ = l.cos_outer;
                          range_ = l.range;
                          color_ = l.intensity;
                          if (l.ies.profile) ies_.emplace(l.ies);
                          if (l.gobo.image) spot_gobo_.emplace(l);
                        },
                        [&](const BoxLight& l) {
                          kind_ = Kind::box;
                          position_ = l.position;
                          direction_ = l.direction;
                          up_ = l.up;
                          right_ = cross(l.direction, l.up);
                          half_width_ = l.half_width;
                          half_height_ = l.half_height;
                          range_ = l.range;
                          color_ = l.irradiance;
                          if (l.gobo.image) box_gobo_.emplace(l.gobo);
                        },
                        [&](const DirectionalLight& l) {
                          kind_ = Kind::directional;
                          direction_ = l.direction;
                          color_ = l.irradiance;
                        }},
             light);
  inv_range_ = kind_ == Kind::box ? 0.0f : inverse_range(range_);
}

LightLanes::Arrival LightLanes::point_like(const Batch& px, const Batch& py, const Batch& pz) const {
  const Batch dx = position_.x - px, dy = position_.y - py, dz = position_.z - pz;
  const Batch dist2 = dx * dx + dy * dy + dz * dz;
  Arrival a;
  a.distance = xsimd::sqrt(dist2);
  const Batch inv = 1.0f / a.distance;
  a.wx = dx * inv, a.wy = dy * inv, a.wz = dz * inv;
  Batch scale = range_window(a.distance, range_, inv_range_) * (inv * inv);
  const Batch ox = -a.wx, oy = -a.wy, oz = -a.wz;  // leaving the light
  if (kind_ == Kind::spot)
    scale *= smoothstep(cos_outer_, cos_inner_, ox * direction_.x + oy * direction_.y + oz * direction_.z);
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

LightLanes::Arrival LightLanes::box(const Batch& px, const Batch& py, const Batch& pz) const {
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

LightLanes::Arrival LightLanes::at(const Batch& px, const Batch& py, const Batch& pz) const {
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
