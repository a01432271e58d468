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

// Maps a world point into the shape's unit-sphere coordinates (the box spans [-1, 1]^3).
struct UnitCoordinates {
  Vec3 p;
  Vec3 operator()(const SphereVolumeShape& s) const { return s.sphere.object_to_world.inverse_point(p); }
  Vec3 operator()(const BoxVolumeShape& b) const {
    const Vec3 q = b.object_to_world.inverse_point(p);
    const Vec3 half = (b.hi - b.lo) * 0.5f;
    return {(q.x - b.lo.x) / half.x - 1.0f, (q.y - b.lo.y) / half.y - 1.0f, (q.z - b.lo.z) / half.z - 1.0f};
  }
};

struct FieldDensity {
  const VolumeShape& shape;
  Vec3 p;
  float operator()(const ConstantDensity&) const { return 1.0f; }
  float operator()(const RadialFalloffDensity& falloff) const {
    const float r2 = length_squared(std::visit(UnitCoordinates{p}, shape));
    return r2 >= 1.0f ? 0.0f : std::pow(1.0f - r2, falloff.exponent);
  }
};

struct ShapeBounds {
  Bounds3 operator()(const SphereVolumeShape& s) const { return s.sphere.world_bounds(); }
  Bounds3 operator()(const BoxVolumeShape& b) const { return b.object_to_world.bounds({b.lo, b.hi}); }
};

struct FieldIsConstant {
  bool operator()(const ConstantDensity&) const { return true; }
  bool operator()(const RadialFalloffDensity&) const { return false; }
};

}  // namespace

std::optional<std::pair<float, float>> volume_interval(const VolumeShape& shape, const Ray& ray) {
  return std::visit(Interval{ray}, shape);
}

Bounds3 volume_bounds(const VolumeShape& shape) { return std::visit(ShapeBounds{}, shape); }

bool is_homogeneous(const VolumeShader& shader) {
  return !shader.noise && std::visit(FieldIsConstant{}, shader.field);
}

float field_density(const VolumePrimitive& primitive, Vec3 p) {
  return std::visit(FieldDensity{primitive.shape, p}, primitive.shader.field);
}

MediumSample shade_volume(const VolumePrimitive& primitive, Vec3 p) {
  const VolumeShader& s = primitive.shader;
  float d = s.density * field_density(primitive, p);
  if (s.noise) d *= noise_density(*s.noise, p);
  return {s.sigma_a * d, s.sigma_s * d, s.emission * d, s.phase};
}

RGB max_sigma_t(const VolumePrimitive& primitive) {
  // Every density field here peaks at 1; noise scales it by at most noise_density_max.
  const VolumeShader& s = primitive.shader;
  const float peak = s.density * (s.noise ? noise_density_max(*s.noise) : 1.0f);
  return (s.sigma_a + s.sigma_s) * peak;
}

}  // namespace caligo
