#include "realtime/media.h"

#include <cmath>

namespace caligo {

bool has_constant_field(const VolumeShader& shader) {
  return std::holds_alternative<ConstantDensity>(shader.field);
}

float mean_medium_density(const VolumePrimitive& primitive, Vec3 p) {
  return primitive.shader.density * field_density(primitive, p);
}

float medium_density(const VolumePrimitive& primitive, Vec3 p) {
  const float d = mean_medium_density(primitive, p);
  return primitive.shader.noise ? d * noise_density(*primitive.shader.noise, p) : d;
}

RGB primitive_optical_depth(const VolumePrimitive& primitive, const Ray& ray, float t0, float t1) {
  const RGB sigma_t = primitive.shader.sigma_a + primitive.shader.sigma_s;
  const float len = t1 - t0;
  if (!(len > 0.0f)) return RGB(0.0f);
  if (has_constant_field(primitive.shader)) return sigma_t * (primitive.shader.density * len);
  // 4-point Gauss-Legendre on [t0, t1].
  constexpr float kX[4] = {-0.8611363116f, -0.3399810436f, 0.3399810436f, 0.8611363116f};
  constexpr float kW[4] = {0.3478548451f, 0.6521451549f, 0.6521451549f, 0.3478548451f};
  const float mid = 0.5f * (t0 + t1), half = 0.5f * len;
  float sum = 0.0f;
  for (int i = 0; i < 4; ++i) sum += kW[i] * mean_medium_density(primitive, ray.at(mid + half * kX[i]));
  return sigma_t * (sum * half);
}

RGB segment_optical_depth(const VolumeScene& volumes, Vec3 a, Vec3 b) {
  const float len = distance(a, b);
  if (!(len > 0.0f)) return RGB(0.0f);
  const Ray ray{a, (b - a) / len, 0.0f, len};
  RGB tau;
  // A linear scan: real-time scenes hold a handful of primitives, and this is the scalar
  // reference path (the SIMD path has its own per-light form).
  for (const VolumePrimitive& primitive : volumes.primitives()) {
    const auto overlap = volume_interval(primitive.shape, ray);
    if (overlap) tau += primitive_optical_depth(primitive, ray, overlap->first, overlap->second);
  }
  return tau;
}

ObjectSpaceShape object_space_shape(const VolumeShape& shape) {
  struct Describe {
    ObjectSpaceShape operator()(const SphereVolumeShape& s) const {
      return from(true, s.sphere.object_to_world.inverse_matrix(), {}, {});
    }
    ObjectSpaceShape operator()(const BoxVolumeShape& b) const {
      return from(false, b.object_to_world.inverse_matrix(), b.lo, b.hi);
    }
    static ObjectSpaceShape from(bool sphere, const Mat4& world_to_object, Vec3 lo, Vec3 hi) {
      ObjectSpaceShape out;
      out.sphere = sphere;
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) out.m[r][c] = world_to_object.m[r][c];
      out.lo = lo;
      out.hi = hi;
      return out;
    }
  };
  return std::visit(Describe{}, shape);
}

}  // namespace caligo
