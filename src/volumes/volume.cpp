#include "volumes/volume.h"

#include <algorithm>
#include <cmath>

#include "core/ray_solids.h"
#include "media/blackbody.h"
#include "volumes/mesh_volume.h"

namespace caligo {
namespace {

std::optional<RayRange> clip(const Ray& ray, float t0, float t1) {
  t0 = std::max(t0, ray.tmin);
  t1 = std::min(t1, ray.tmax);
  if (!(t0 < t1)) return std::nullopt;
  return RayRange{t0, t1};
}

// Slab test in object space; t is the same parameter in both spaces (affine map).
std::optional<RayRange> box_interval(const Transform& object_to_world, Vec3 lo, Vec3 hi, const Ray& ray) {
  const auto range = ray_box(object_to_world.inverse_point(ray.origin), object_to_world.inverse_vector(ray.direction),
                             lo, hi, -kInfinity, kInfinity);
  return range ? clip(ray, range->t0, range->t1) : std::nullopt;
}

struct HullInterval {
  const Ray& ray;
  std::optional<RayRange> operator()(const SphereVolumeShape& s) const {
    const auto roots = intersect_sphere(s.sphere, ray);
    if (!roots) return std::nullopt;
    return clip(ray, roots->t0, roots->t1);
  }
  std::optional<RayRange> operator()(const BoxVolumeShape& b) const {
    return box_interval(b.object_to_world, b.lo, b.hi, ray);
  }
  std::optional<RayRange> operator()(const MeshVolumeShape& m) const {
    const Bounds3 b = m.mesh->bounds();
    return box_interval(Transform(), b.lo, b.hi, ray);
  }
  // A ray escaping the scene inside a medium ends at a finite 1e30: sigma * t stays finite
  // (0 for a channel the medium does not attenuate, where sigma * inf would be NaN) and the
  // transmittance there is exactly 0 or 1, as at infinity.
  std::optional<RayRange> operator()(const UnboundedVolumeShape&) const { return clip(ray, -kInfinity, 1.0e30f); }
};

// The stretches of the ray inside the shape, into context.mesh_intervals (reused scratch).
struct InsideRanges {
  const Ray& ray;
  VolumeContext& context;
  void operator()(const SphereVolumeShape& s) const { one(HullInterval{ray}(s)); }
  void operator()(const BoxVolumeShape& b) const { one(HullInterval{ray}(b)); }
  void operator()(const MeshVolumeShape& m) const {
    context.mesh_intervals.clear();
    m.mesh->intervals(ray, context.mesh_hits, context.mesh_intervals);
  }
  void operator()(const UnboundedVolumeShape& u) const { one(HullInterval{ray}(u)); }
  void one(std::optional<RayRange> s) const {
    context.mesh_intervals.clear();
    if (s) context.mesh_intervals.push_back(*s);
  }
};

// Maps a world point into the shape's unit-sphere coordinates (boxes and meshes map their
// bounds to [-1, 1]^3).
Vec3 box_unit(Vec3 q, Vec3 lo, Vec3 hi) {
  const Vec3 half = (hi - lo) * 0.5f;
  return {(q.x - lo.x) / half.x - 1.0f, (q.y - lo.y) / half.y - 1.0f, (q.z - lo.z) / half.z - 1.0f};
}
struct UnitCoordinates {
  Vec3 p;
  Vec3 operator()(const SphereVolumeShape& s) const { return s.sphere.object_to_world.inverse_point(p); }
  Vec3 operator()(const BoxVolumeShape& b) const { return box_unit(b.object_to_world.inverse_point(p), b.lo, b.hi); }
  Vec3 operator()(const MeshVolumeShape& m) const { return box_unit(p, m.mesh->bounds().lo, m.mesh->bounds().hi); }
  Vec3 operator()(const UnboundedVolumeShape&) const { return Vec3(0.0f); }  // constant fields only
};

struct FieldDensity {
  const VolumeShape& shape;
  Vec3 p;
  VolumeContext& context;
  float operator()(const ConstantDensity&) const { return 1.0f; }
  float operator()(const RadialFalloffDensity& falloff) const {
    const float r2 = length_squared(std::visit(UnitCoordinates{p}, shape));
    return r2 >= 1.0f ? 0.0f : std::pow(1.0f - r2, falloff.exponent);
  }
  float operator()(const HeightFalloffDensity& h) const { return h.at(p.y); }
  float operator()(const GridDensity& g) const {
    return g.grid->density(g.grid_to_world.inverse_point(p), g.filter, *context.grids);
  }
};

struct ShapeBounds {
  Bounds3 operator()(const SphereVolumeShape& s) const { return s.sphere.world_bounds(); }
  Bounds3 operator()(const BoxVolumeShape& b) const { return b.object_to_world.bounds({b.lo, b.hi}); }
  Bounds3 operator()(const MeshVolumeShape& m) const { return m.mesh->bounds(); }
  Bounds3 operator()(const UnboundedVolumeShape&) const {
    return {Vec3(-kInfinity), Vec3(kInfinity)};
  }
};

struct FieldIsConstant {
  bool operator()(const ConstantDensity&) const { return true; }
  bool operator()(const RadialFalloffDensity&) const { return false; }
  bool operator()(const HeightFalloffDensity&) const { return false; }
  bool operator()(const GridDensity&) const { return false; }
};

// Splits one inside stretch by the field: analytic fields keep it whole, a grid cuts it into
// its occupied block runs, each with its own majorant.
struct FieldIntervals {
  const VolumePrimitive& primitive;
  uint32_t id;
  const Ray& ray;
  RayRange stretch;
  VolumeContext& context;
  RGB sigma_unit;    // sigma_t per unit field density (density and noise peak included)
  bool noise_free;

  // sigma_t per unit field density that holds everywhere (the control of residual ratio
  // tracking): noise may take density to 0, and a colour grid may tint scattering down to 0.
  RGB control_unit() const {
    const VolumeShader& s = primitive.shader;
    if (!noise_free) return RGB(0.0f);
    const bool tinted = s.tint_with_color_grid && std::holds_alternative<GridDensity>(s.field) &&
                        std::get<GridDensity>(s.field).grid->has_color();
    return (s.sigma_a + RGB(s.holdout) + (tinted ? RGB(0.0f) : s.sigma_s)) * s.density;
  }

  void operator()(const ConstantDensity&) const {
    context.intervals.push_back({stretch.t0, stretch.t1, id, sigma_unit, noise_free, control_unit()});
  }
  void operator()(const RadialFalloffDensity&) const {
    context.intervals.push_back({stretch.t0, stretch.t1, id, sigma_unit, false});
  }
  // The density is largest at the stretch's lowest point, one of its ends.
  void operator()(const HeightFalloffDensity& h) const {
    const float y0 = ray.at(stretch.t0).y, y1 = ray.at(stretch.t1).y;
    context.intervals.push_back({stretch.t0, stretch.t1, id, sigma_unit * h.at(std::min(y0, y1)), false});
  }
  void operator()(const GridDensity& g) const {
    if (!context.skip_empty_blocks) {
      context.intervals.push_back(
          {stretch.t0, stretch.t1, id, sigma_unit * g.grid->max_density(), false});
      return;
    }
    const Ray local{g.grid_to_world.inverse_point(ray.origin), g.grid_to_world.inverse_vector(ray.direction),
                    ray.tmin, ray.tmax};
    context.grid_intervals.clear();
    g.grid->intervals(local, stretch.t0, stretch.t1, context.grid_intervals);
    const RGB control = control_unit();
    for (const GridInterval& gi : context.grid_intervals)
      context.intervals.push_back({gi.t0, gi.t1, id, sigma_unit * gi.density_max,
                                   gi.constant && noise_free && context.constant_blocks_one_step,
                                   control * gi.density_min});
  }
};

// Hotter than any flame by far, and low enough that sigma T^4 stays finite in float.
constexpr float kMaxKelvin = 1e6f;

RGB blackbody_emission(const BlackbodyEmission& b, float raw_temperature) {
  if (!(raw_temperature > 0.0f)) return RGB(0.0f);
  const float kelvin = std::min(raw_temperature * b.temperature_scale + b.temperature_offset, kMaxKelvin);
  if (!(kelvin > 0.0f)) return RGB(0.0f);
  return blackbody_color(kelvin) * (b.intensity * blackbody_exitance_radiance(kelvin));
}

RGB clamp01(RGB c) {
  return {std::clamp(c.r, 0.0f, 1.0f), std::clamp(c.g, 0.0f, 1.0f), std::clamp(c.b, 0.0f, 1.0f)};
}

struct Shade {
  const VolumePrimitive& primitive;
  Vec3 p;
  VolumeContext& context;
  MediumSample with_density(float d) const {
    const VolumeShader& s = primitive.shader;
    if (s.noise) d *= noise_density(*s.noise, p);
    return {s.sigma_a * d, s.sigma_s * d, s.emission * d, s.phase, s.holdout * d};
  }
  MediumSample operator()(const ConstantDensity&) const { return with_density(primitive.shader.density); }
  MediumSample operator()(const RadialFalloffDensity& f) const {
    return with_density(primitive.shader.density * FieldDensity{primitive.shape, p, context}(f));
  }
  MediumSample operator()(const HeightFalloffDensity& h) const {
    return with_density(primitive.shader.density * h.at(p.y));
  }
  MediumSample operator()(const GridDensity& g) const {
    const VolumeShader& s = primitive.shader;
    const GridValues v = g.grid->values(g.grid_to_world.inverse_point(p), g.filter, *context.grids);
    MediumSample m = with_density(s.density * v.density);
    if (s.tint_with_color_grid && g.grid->has_color()) m.sigma_s *= clamp01(v.color);
    if (s.blackbody) m.emission += blackbody_emission(*s.blackbody, v.temperature);
    if (s.flame && v.flame > 0.0f) m.emission += s.flame->color * (s.flame->intensity * v.flame);
    return m;
  }
};

struct FieldVoxelSize {
  float operator()(const ConstantDensity&) const { return kInfinity; }
  float operator()(const RadialFalloffDensity&) const { return kInfinity; }
  float operator()(const HeightFalloffDensity&) const { return kInfinity; }
  float operator()(const GridDensity& g) const {
    // The placement may scale: a voxel's world length is the grid's times the smallest axis scale.
    float scale = kInfinity;
    for (const Vec3 axis : {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)})
      scale = std::min(scale, length(g.grid_to_world.vector(axis)));
    return g.grid->voxel_size() * scale;
  }
};

float noise_peak(const VolumeShader& s) { return s.noise ? noise_density_max(*s.noise) : 1.0f; }

}  // namespace

float height_fog_depth(const HeightFalloffDensity& f, float oy, float dy, float t0, float t1) {
  if (!(t1 > t0)) return 0.0f;
  // The level of `base` along the ray splits [t0, t1] into a part below (density 1) and above.
  float below = 0.0f, a = t0, b = t1;
  const float ya = oy + dy * t0, yb = oy + dy * t1;
  if (ya <= f.base && yb <= f.base) return t1 - t0;
  if (ya < f.base || yb < f.base) {
    const float tc = t0 + (f.base - ya) / (yb - ya) * (t1 - t0);  // where y = base
    below = ya < f.base ? tc - t0 : t1 - tc;
    (ya < f.base ? a : b) = tc;
  }
  // Above: from the lower end, e^(-(y_low - base)/H) len (1 - e^(-g)) / g with g = |dy| len / H.
  const float len = b - a;
  const float y_low = std::max(f.base, std::min(oy + dy * a, oy + dy * b));
  const float g = std::abs(dy) * len / f.scale_height;
  const float shape = g > 1e-4f ? -std::expm1(-g) / g : 1.0f - 0.5f * g;
  return below + f.at(y_low) * len * shape;
}

std::optional<RayRange> volume_hull_interval(const VolumeShape& shape, const Ray& ray) {
  return std::visit(HullInterval{ray}, shape);
}

void append_intervals(const VolumePrimitive& primitive, uint32_t id, const Ray& ray, VolumeContext& context) {
  std::visit(InsideRanges{ray, context}, primitive.shape);
  if (context.mesh_intervals.empty()) return;
  const VolumeShader& s = primitive.shader;
  const RGB sigma_unit = (s.sigma_a + s.sigma_s + RGB(s.holdout)) * (s.density * noise_peak(s));
  for (const RayRange& stretch : context.mesh_intervals)
    std::visit(FieldIntervals{primitive, id, ray, stretch, context, sigma_unit, !s.noise}, s.field);
}

Bounds3 volume_bounds(const VolumeShape& shape) { return std::visit(ShapeBounds{}, shape); }

bool is_homogeneous(const VolumeShader& shader) {
  return !shader.noise && std::visit(FieldIsConstant{}, shader.field);
}

float field_density(const VolumePrimitive& primitive, Vec3 p, VolumeContext& context) {
  return std::visit(FieldDensity{primitive.shape, p, context}, primitive.shader.field);
}

MediumSample shade_volume(const VolumePrimitive& primitive, Vec3 p, VolumeContext& context) {
  return std::visit(Shade{primitive, p, context}, primitive.shader.field);
}

float field_voxel_size(const VolumePrimitive& primitive) {
  return std::visit(FieldVoxelSize{}, primitive.shader.field);
}

}  // namespace caligo
