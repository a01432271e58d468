#include "scene/animation.h"

#include <algorithm>
#include <cmath>

#include "lights/light.h"

namespace caligo {
namespace {

// Rate of change at key i (per second): central difference, one-sided at the ends.
Vec3 key_velocity(const std::vector<float>& t, const std::vector<Vec3>& p, size_t i) {
  const size_t lo = i == 0 ? 0 : i - 1;
  const size_t hi = std::min(i + 1, p.size() - 1);
  return (p[hi] - p[lo]) / (t[hi] - t[lo]);
}

// One channel of a light's keys: the keys that give it, in time order.
struct Channel {
  std::vector<float> times;
  std::vector<Vec3> values;
};

Channel channel(const std::vector<LightKey>& keys, std::optional<Vec3> LightKey::*member) {
  Channel c;
  for (const LightKey& k : keys) {
    if (!(k.*member)) continue;
    c.times.push_back(k.time);
    c.values.push_back(*(k.*member));
  }
  return c;
}

std::optional<Vec3> sample(const Channel& c, Interpolation mode, float time) {
  if (c.times.empty()) return std::nullopt;
  return interpolate_keys(c.times, c.values, mode, time);
}

// Interpolated directions are renormalised; where keys point opposite ways the blend can
// vanish, and the nearer key's direction is used instead.
std::optional<Vec3> sample_direction(const Channel& c, Interpolation mode, float time) {
  const auto d = sample(c, mode, time);
  if (!d) return std::nullopt;
  if (length_squared(*d) > 1e-12f) return normalize(*d);
  const size_t i = size_t(std::lower_bound(c.times.begin(), c.times.end(), time) - c.times.begin());
  return normalize(c.values[std::min(i, c.values.size() - 1)]);
}

}  // namespace

Vec3 interpolate_keys(const std::vector<float>& t, const std::vector<Vec3>& p, Interpolation mode,
                      float time) {
  if (time <= t.front()) return p.front();
  if (time >= t.back()) return p.back();
  const size_t i = size_t(std::upper_bound(t.begin(), t.end(), time) - t.begin()) - 1;
  const float h = t[i + 1] - t[i];
  const float s = (time - t[i]) / h;
  if (mode == Interpolation::linear) return p[i] * (1.0f - s) + p[i + 1] * s;
  // Cubic Hermite basis with tangents scaled from per-second to per-segment.
  const float s2 = s * s, s3 = s2 * s;
  const float h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
  return p[i] * h00 + key_velocity(t, p, i) * (h * h10) + p[i + 1] * h01 +
         key_velocity(t, p, i + 1) * (h * h11);
}

CameraDesc SceneDesc::camera_at(float time) const {
  CameraDesc out = camera;
  if (camera.path.empty()) return out;
  std::vector<float> times;
  std::vector<Vec3> positions, targets;
  for (const CameraKey& k : camera.path) {
    times.push_back(k.time);
    positions.push_back(k.position);
    targets.push_back(k.look_at);
  }
  out.position = interpolate_keys(times, positions, camera.path_interpolation, time);
  out.look_at = interpolate_keys(times, targets, camera.path_interpolation, time);
  out.path.clear();
  return out;
}

std::vector<Light> SceneDesc::lights_at(float time) const {
  std::vector<Light> out = lights;
  for (size_t i = 0; i < out.size(); ++i) {
    const LightOptions& o = options(i);
    pose_light(out[i], {sample(channel(o.animation, &LightKey::position), o.interpolation, time),
                        sample_direction(channel(o.animation, &LightKey::direction), o.interpolation, time), time});
  }
  return out;
}

std::vector<VolumePrimitive> SceneDesc::volumes_at(float time) const {
  std::vector<VolumePrimitive> out = volumes;
  for (VolumePrimitive& v : out) {
    if (!v.shader.noise) continue;
    v.shader.noise->offset += v.shader.noise->wind * time;
    v.shader.noise->wind = Vec3();
  }
  return out;
}

bool SceneDesc::media_move() const {
  return std::any_of(volumes.begin(), volumes.end(), [](const VolumePrimitive& v) {
    return v.shader.noise && !(v.shader.noise->wind == Vec3());
  });
}

SceneDesc SceneDesc::at_time(float time) const {
  SceneDesc out = *this;
  out.camera = camera_at(time);
  out.lights = lights_at(time);
  for (LightOptions& o : out.light_options) o.animation.clear();
  out.volumes = volumes_at(time);
  return out;
}

float SceneDesc::duration() const {
  float end = 0.0f;
  if (!camera.path.empty()) end = std::max(end, camera.path.back().time);
  for (const LightOptions& o : light_options)
    if (!o.animation.empty()) end = std::max(end, o.animation.back().time);
  return end;
}

}  // namespace caligo
