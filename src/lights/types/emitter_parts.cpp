#include "lights/types/emitter_parts.h"

#include <cmath>

#include "core/ray_solids.h"
#include "lights/gobo.h"
#include "lights/ies.h"

namespace caligo::emitter {

float area_to_solid_angle(float area_pdf, Vec3 receiver, Vec3 on_light, Vec3 light_normal) {
  const Vec3 d = on_light - receiver;
  const float dist2 = length_squared(d);
  const float cos_light = std::abs(dot(light_normal, d)) / std::sqrt(dist2);
  if (cos_light <= 0.0f) return 0.0f;
  return area_pdf * dist2 / cos_light;
}

std::optional<LightSample> area_point(Vec3 receiver, Vec3 p, Vec3 n, float area, RGB emitted_towards_receiver) {
  const Vec3 d = p - receiver;
  const float dist = length(d);
  if (!(dist > 0.0f) || emitted_towards_receiver.is_black()) return std::nullopt;
  const Vec3 wi = d / dist;
  const float pdf = area_to_solid_angle(1.0f / area, receiver, p, n);
  if (!(pdf > 0.0f) || !std::isfinite(pdf)) return std::nullopt;
  return LightSample{emitted_towards_receiver, wi, dist, pdf, false};
}

std::optional<LightSample> solid_angle_point(Vec3 receiver, std::optional<Vec3> p, double omega, RGB radiance) {
  if (!p || radiance.is_black()) return std::nullopt;
  const Vec3 d = *p - receiver;
  const float dist = length(d);
  if (!(dist > 0.0f)) return std::nullopt;
  return LightSample{radiance, d / dist, dist, float(1.0 / omega), false};
}

std::optional<LightSample> from_arrival(std::optional<DeltaArrival> a) {
  if (!a) return std::nullopt;
  return LightSample{a->radiance, a->wi, a->distance, 1.0f, true};
}

std::optional<RayRange> whole(float tmin, float tmax) { return clip_range(tmin, tmax, tmin, tmax); }

std::optional<RayRange> within_range(Vec3 origin, Vec3 dir, Vec3 centre, float range, float tmin, float tmax) {
  return std::isfinite(range) ? ray_ball(origin, dir, centre, range, tmin, tmax) : whole(tmin, tmax);
}

float ies_mean(const IesAttachment& ies) { return ies.profile ? ies.profile->mean() : 1.0f; }
float gobo_mean(const Gobo& gobo) { return gobo.image ? gobo.image->mean().average() : 1.0f; }

namespace {

// Keeps `up` a unit vector perpendicular to `direction` (Gram-Schmidt), falling back to any
// perpendicular when the new direction is parallel to the old up.
Vec3 orthogonal_up(Vec3 up, Vec3 direction) {
  const Vec3 u = up - direction * dot(up, direction);
  if (length_squared(u) > 1e-8f) return normalize(u);
  return Frame::from_z(direction).t;
}

}  // namespace

void pose_aimed_parts(Vec3& position, Vec3& direction, Vec3& up, Gobo& gobo, const LightPose& at) {
  if (at.position) position = *at.position;
  if (at.direction) {
    direction = *at.direction;
    up = orthogonal_up(up, direction);
  }
  gobo.offset = {gobo.offset.x + gobo.scroll.x * at.time, gobo.offset.y + gobo.scroll.y * at.time};
  gobo.rotation += gobo.spin * at.time;
  gobo.scroll = {};
  gobo.spin = 0.0f;
}

}  // namespace caligo::emitter
