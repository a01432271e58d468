#include "volumes/volume.h"

#include <algorithm>
#include <cmath>

namespace caligo {
namespace {

struct Interval {
  const Ray& ray;
  std::optional<std::pair<float, float>> clip(float t0, float t1) const {
    t0 = std::max(t0, ray.tmin);
    t1 = std::min(t1, ray.tmax);
    if (!(t0 < t1)) return std::nullopt;
    return std::make_pair(t0, t1);
  }
  std::optional<std::pair<float, float>> operator()(const SphereVolumeShape& s) const {
    const auto roots = intersect_sphere(s.sphere, ray);
    if (!roots) return std::nullopt;
    return clip(roots->t_near, roots->t_far);
  }
  // Slab test in object space; t is the same parameter in both spaces (affine map).
  std::optional<std::pair<float, float>> operator()(const BoxVolumeShape& b) const {
    const Vec3 o = b.object_to_world.inverse_point(ray.origin);
    const Vec3 d = b.object_to_world.inverse_vector(ray.direction);
    float t0 = -kInfinity, t1 = kInfinity;
    for (int a = 0; a < 3; ++a) {
      const float inv = 1.0f / d[a];
      float tn = (b.lo[a] - o[a]) * inv, tf = (b.hi[a] - o[a]) * inv;
      if (std::isnan(tn) || std::isnan(tf)) {  // parallel to the slab and on its plane
        if (o[a] < b.lo[a] || o[a] > b.hi[a]) return std::nullopt;
        continue;
      }
      if (tn > tf) std::swap(tn, tf);
      t0 = std::max(t0, tn);
      t1 = std::min(t1, tf);
    }
    return clip(t0, t1);
  }
};

float density_at(const DensityField& field, const VolumeShape& shape, Vec3 p) {
  if (std::holds_alternative<ConstantDensity>(field)) return 1.0f;
  const auto& falloff = std::get<RadialFalloffDensity>(field);
  Vec3 local;
  if (const auto* s = std::get_if<SphereVolumeShape>(&shape)) {
    local = s->sphere.object_to_world.inverse_point(p);
  } else {
    const auto& b = std::get<BoxVolumeShape>(shape);
    const Vec3 q = b.object_to_world.inverse_point(p);
    const Vec3 half = (b.hi - b.lo) * 0.5f;
    local =
        Vec3((q.x - b.lo.x) / half.x - 1.0f, (q.y - b.lo.y) / half.y - 1.0f, (q.z - b.lo.z) / half.z - 1.0f);
  }
  const float r2 = length_squared(local);
  return r2 >= 1.0f ? 0.0f : std::pow(1.0f - r2, falloff.exponent);
}

}  // namespace

std::optional<std::pair<float, float>> volume_interval(const VolumeShape& shape, const Ray& ray) {
  return std::visit(Interval{ray}, shape);
}

Bounds3 volume_bounds(const VolumeShape& shape) {
  if (const auto* s = std::get_if<SphereVolumeShape>(&shape)) return s->sphere.world_bounds();
  const auto& b = std::get<BoxVolumeShape>(shape);
  return b.object_to_world.bounds({b.lo, b.hi});
}

bool is_homogeneous(const VolumeShader& shader) {
  return std::holds_alternative<ConstantDensity>(shader.field);
}

MediumSample shade_volume(const VolumePrimitive& primitive, Vec3 p) {
  const VolumeShader& s = primitive.shader;
  const float d = s.density * density_at(s.field, primitive.shape, p);
  return {s.sigma_a * d, s.sigma_s * d, s.emission * d, s.phase};
}

RGB max_sigma_t(const VolumePrimitive& primitive) {
  // Every density field here peaks at 1.
  return (primitive.shader.sigma_a + primitive.shader.sigma_s) * primitive.shader.density;
}

}  // namespace caligo
