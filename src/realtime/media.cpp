#include "realtime/media.h"

#include <algorithm>
#include <cmath>

#include "volumes/mesh_volume.h"

namespace caligo {

bool has_constant_field(const VolumePrimitive& primitive) {
  // A mesh volume is constant inside but not over its box: the lanes' box test would overfill it.
  return std::holds_alternative<ConstantDensity>(primitive.shader.field) &&
         !std::holds_alternative<MeshVolumeShape>(primitive.shape);
}

namespace {
// The real-time passes' own per-thread volume state (grid accessors, interval lists).
VolumeContext& context() {
  thread_local VolumeContext c;
  return c;
}
}  // namespace

float mean_medium_density(const VolumePrimitive& primitive, Vec3 p) {
  return primitive.shader.density * field_density(primitive, p, context());
}

float medium_density(const VolumePrimitive& primitive, Vec3 p) {
  const float d = mean_medium_density(primitive, p);
  return primitive.shader.noise ? d * noise_density(*primitive.shader.noise, p) : d;
}

RGB primitive_optical_depth(const VolumePrimitive& primitive, const Ray& ray, float t0, float t1) {
  const RGB sigma_t = primitive.shader.sigma_a + primitive.shader.sigma_s;
  const float len = t1 - t0;
  if (!(len > 0.0f)) return RGB(0.0f);
  if (std::holds_alternative<ConstantDensity>(primitive.shader.field)) return sigma_t * (primitive.shader.density * len);
  // Height fog in closed form (the noise on it, if any, at its mean factor 1).
  if (const auto* h = std::get_if<HeightFalloffDensity>(&primitive.shader.field))
    return sigma_t * (primitive.shader.density * height_fog_depth(*h, ray.origin.y, ray.direction.y, t0, t1));
  // 4-point Gauss-Legendre panels on [t0, t1]: one for an analytic field, one per few
  // voxels for a grid (a trilinear field is piecewise cubic along a ray, between voxel faces).
  constexpr float kX[4] = {-0.8611363116f, -0.3399810436f, 0.3399810436f, 0.8611363116f};
  constexpr float kW[4] = {0.3478548451f, 0.6521451549f, 0.6521451549f, 0.3478548451f};
  constexpr float kVoxelsPerPanel = 2.0f;
  const float voxel = field_voxel_size(primitive);
  const int panels =
      std::isfinite(voxel) ? int(std::clamp(std::ceil(len / (kVoxelsPerPanel * voxel)), 1.0f, 4096.0f)) : 1;
  const float width = len / float(panels), half = 0.5f * width;
  float sum = 0.0f;
  for (int k = 0; k < panels; ++k) {
    const float mid = t0 + (float(k) + 0.5f) * width;
    for (int i = 0; i < 4; ++i) sum += kW[i] * mean_medium_density(primitive, ray.at(mid + half * kX[i]));
  }
  return sigma_t * (sum * half);
}

RGB primitive_segment_optical_depth(const VolumePrimitive& primitive, const Ray& ray) {
  VolumeContext& ctx = context();
  ctx.intervals.clear();
  append_intervals(primitive, 0, ray, ctx);
  RGB tau;
  for (const VolumeInterval& iv : ctx.intervals) tau += primitive_optical_depth(primitive, ray, iv.t0, iv.t1);
  return tau;
}

void add_depth_profile(const VolumePrimitive& primitive, const Ray& ray, std::span<const float> nodes, RGB* out) {
  VolumeContext& ctx = context();
  ctx.intervals.clear();
  append_intervals(primitive, 0, ray, ctx);
  const std::vector<VolumeInterval> intervals = ctx.intervals;  // primitive_optical_depth reuses ctx
  RGB sum;
  float from = 0.0f;
  for (size_t k = 0; k < nodes.size(); ++k) {
    const float to = nodes[k];
    for (const VolumeInterval& iv : intervals) {
      const float a = std::max(from, iv.t0), b = std::min(to, iv.t1);
      if (b > a) sum += primitive_optical_depth(primitive, ray, a, b);
    }
    out[k] += sum;
    from = to;
  }
}

RGB segment_optical_depth(const VolumeScene& volumes, Vec3 a, Vec3 b) {
  const float len = distance(a, b);
  if (!(len > 0.0f)) return RGB(0.0f);
  const Ray ray{a, (b - a) / len, 0.0f, len};
  RGB tau;
  // A linear scan: real-time scenes hold a handful of primitives, and this is the scalar
  // reference path (the SIMD path has its own per-light form).
  for (const VolumePrimitive& primitive : volumes.primitives()) tau += primitive_segment_optical_depth(primitive, ray);
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
    // The mesh's bounding box: only homogeneous lanes use this shape, and a mesh volume is
    // never one (has_constant_field is false for it), so the box only culls.
    ObjectSpaceShape operator()(const MeshVolumeShape& m) const {
      return from(false, Mat4::identity(), m.mesh->bounds().lo, m.mesh->bounds().hi);
    }
    // Surface-bounded media never reach the real-time pipeline (it reads the scene's volume
    // primitives only); described as the box of all finite space.
    ObjectSpaceShape operator()(const UnboundedVolumeShape&) const {
      return from(false, Mat4::identity(), Vec3(-1e30f), Vec3(1e30f));
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
