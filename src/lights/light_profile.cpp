#include "lights/light_profile.h"

#include <algorithm>
#include <cmath>

#include "core/math.h"
#include "lights/gobo.h"
#include "lights/ies.h"

namespace caligo {

float range_window(float distance, float range) {
  if (!(range < kInfinity)) return 1.0f;
  if (!(distance < range)) return 0.0f;
  const float x = sqr(sqr(distance / range));
  return sqr(1.0f - x);
}

float spot_cone(const SpotLight& light, Vec3 w_from_light) {
  return smoothstep(light.cos_outer, light.cos_inner, dot(light.direction, w_from_light));
}

RGB gobo_filter(const Gobo& gobo, Vec2 uv) {
  if (!gobo.image) return RGB(1.0f);
  // Rotate about the image centre, then shift; the image wraps.
  const float c = std::cos(gobo.rotation), s = std::sin(gobo.rotation);
  const float x = uv.x - 0.5f, y = uv.y - 0.5f;
  const Vec2 st{c * x - s * y + 0.5f + gobo.offset.x, s * x + c * y + 0.5f + gobo.offset.y};
  return gobo.image->lookup(st);
}

Vec2 spot_gobo_uv(const SpotLight& light, Vec3 w_from_light) {
  const Vec3 right = cross(light.direction, light.up);
  const float z = dot(w_from_light, light.direction);
  // The outer cone's half-angle tangent spans half the texture. Directions at or behind the
  // light's plane have no projection; the cone gives them no light anyway.
  if (!(z > 1e-6f)) return {-1.0f, -1.0f};
  const float tan_outer = safe_sqrt(1.0f - sqr(light.cos_outer)) / std::fmax(light.cos_outer, 1e-6f);
  const float scale = 0.5f / (z * std::fmax(tan_outer, 1e-6f));
  return {0.5f + dot(w_from_light, right) * scale, 0.5f + dot(w_from_light, light.up) * scale};
}

float ies_factor(const IesAttachment& ies, Vec3 w_from_light) {
  if (!ies.profile) return 1.0f;
  const Frame frame = Frame::from_z(ies.axis);
  const Vec3 local = frame.to_local(w_from_light);
  const float vertical = std::acos(std::clamp(local.z, -1.0f, 1.0f));
  float horizontal = std::atan2(local.y, local.x);
  if (horizontal < 0.0f) horizontal += 2.0f * kPi;
  return ies.profile->evaluate(vertical, horizontal);
}

namespace {

// Direction and distance from a receiver to a light at `position`; nullopt at the light itself.
struct ToLight {
  Vec3 wi;  // unit, towards the light
  float dist, dist2;
};
std::optional<ToLight> to_light(Vec3 position, Vec3 receiver) {
  const Vec3 d = position - receiver;
  const float dist2 = length_squared(d);
  if (!(dist2 > 0.0f)) return std::nullopt;
  const float dist = std::sqrt(dist2);
  return ToLight{d / dist, dist, dist2};
}

}  // namespace

std::optional<DeltaArrival> delta_arrival(const PointLight& light, Vec3 receiver) {
  const auto to = to_light(light.position, receiver);
  if (!to) return std::nullopt;
  const auto [wi, dist, dist2] = *to;
  const float scale = range_window(dist, light.range) * ies_factor(light.ies, -wi) / dist2;
  if (!(scale > 0.0f)) return std::nullopt;
  return DeltaArrival{light.intensity * scale, wi, dist};
}

std::optional<DeltaArrival> delta_arrival(const SpotLight& light, Vec3 receiver) {
  const auto to = to_light(light.position, receiver);
  if (!to) return std::nullopt;
  const auto [wi, dist, dist2] = *to;
  const Vec3 w_from_light = -wi;
  const float scale =
      spot_cone(light, w_from_light) * range_window(dist, light.range) * ies_factor(light.ies, w_from_light);
  if (!(scale > 0.0f)) return std::nullopt;
  const RGB radiance =
      light.intensity * gobo_filter(light.gobo, spot_gobo_uv(light, w_from_light)) * (scale / dist2);
  if (radiance.is_black()) return std::nullopt;
  return DeltaArrival{radiance, wi, dist};
}

std::optional<DeltaArrival> delta_arrival(const BoxLight& light, Vec3 receiver) {
  const Vec3 local = receiver - light.position;
  const float along = dot(local, light.direction);
  if (!(along >= 0.0f && along <= light.range)) return std::nullopt;
  const Vec3 right = cross(light.direction, light.up);
  const float x = dot(local, right), y = dot(local, light.up);
  if (!(std::abs(x) <= light.half_width && std::abs(y) <= light.half_height)) return std::nullopt;
  const Vec2 uv{0.5f + 0.5f * x / light.half_width, 0.5f + 0.5f * y / light.half_height};
  const RGB radiance = light.irradiance * gobo_filter(light.gobo, uv);
  if (radiance.is_black()) return std::nullopt;
  return DeltaArrival{radiance, -light.direction, along};
}

}  // namespace caligo
