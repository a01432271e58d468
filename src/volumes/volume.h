// Volume primitives (the seed's "volume primitives": IOR 1, no boundary, additive overlap):
// a shape bounding the medium, a density field over it and a shader giving the medium's
// coefficients at a point. A primitive turns a ray into majorant intervals
// (append_intervals); marching and delta tracking take those, not the shape.
// Closed sets are std::variants dispatched by exhaustive std::visit in volume.cpp: a new
// shape or field does not compile until every visitor handles it.
#pragma once

#include <cmath>
#include <memory>
#include <optional>
#include <variant>

#include "core/ray.h"
#include "core/ray_range.h"
#include "core/transform.h"
#include "geometry/shapes.h"
#include "grids/volume_grid.h"
#include "media/medium.h"
#include "volumes/noise.h"
#include "volumes/volume_context.h"

namespace caligo {

class MeshVolume;

// A transformed axis-aligned box [lo, hi] (object space).
struct BoxVolumeShape {
  Transform object_to_world;
  Vec3 lo, hi;
};
struct SphereVolumeShape {
  Sphere sphere;
};
// The inside of a closed triangle mesh, found per ray by even/odd hit counting.
struct MeshVolumeShape {
  std::shared_ptr<const MeshVolume> mesh;
};
// Everywhere along the ray: the interior medium of a surface (materials/material.h), whose
// extent the medium stack tracks (media/medium_stack.h), not a shape. Only homogeneous media
// (constant field, no noise) take this shape: there is no object space to place a field in.
struct UnboundedVolumeShape {};
using VolumeShape = std::variant<SphereVolumeShape, BoxVolumeShape, MeshVolumeShape, UnboundedVolumeShape>;

// Density multipliers over the primitive.
struct ConstantDensity {};
// 1 at the centre falling to 0 at the boundary of the unit sphere (the shape's object space;
// a box or mesh maps its bounds to [-1, 1]^3): (1 - r^2)^exponent. A soft spherical puff.
struct RadialFalloffDensity {
  float exponent = 1.0f;
};
// Exponential height fog (the ground fog of Unreal's and Frostbite's height fog): 1 at and below
// the world height `base`, e^(-(y - base) / scale_height) above it. World space, unlike the
// radial falloff: a tilted box of it still thins upwards. Its optical depth along a straight
// segment has a closed form (height_fog_depth), which the real-time passes use.
struct HeightFalloffDensity {
  float base = 0.0f;
  float scale_height = 1.0f;  // > 0, metres
  float at(float y) const { return y <= base ? 1.0f : std::exp(-(y - base) / scale_height); }
};
// The integral of HeightFalloffDensity::at along o + t d (d unit) over [t0, t1]: the part
// below `base` counts its length, the part above (H / d_y)(f(y_a) - f(y_b)), written with expm1
// so a nearly level segment keeps its accuracy.
float height_fog_depth(const HeightFalloffDensity& f, float oy, float dy, float t0, float t1);

// A sparse grid (VDB, NanoVDB or dense) placed by `grid_to_world`; its other channels
// (temperature, flame, Cd) feed the shader's emission and tint.
struct GridDensity {
  std::shared_ptr<const VolumeGrid> grid;
  Transform grid_to_world;
  GridFilter filter = GridFilter::kTrilinear;
};
using DensityField = std::variant<ConstantDensity, RadialFalloffDensity, HeightFalloffDensity, GridDensity>;

// Emission from a grid's temperature channel: T = raw * scale + offset (Kelvin) emits
// intensity * blackbody_color(T) * sigma_SB T^4 / pi (the colour normalised to luminance 1,
// the magnitude a blackbody's radiance), where the raw temperature is positive.
struct BlackbodyEmission {
  float intensity = 1.0f;
  float temperature_scale = 1.0f;
  float temperature_offset = 0.0f;
};
// Emission from a grid's flame channel: flame * intensity * color.
struct FlameEmission {
  RGB color{1.0f};
  float intensity = 1.0f;
};

struct VolumeShader {
  RGB sigma_a;   // 1/m at density 1
  RGB sigma_s;   // 1/m at density 1
  RGB emission;  // W m^-3 sr^-1 at density 1
  float density = 1.0f;
  PhaseFunction phase;
  DensityField field;
  std::optional<NoiseModulation> noise;  // multiplies the field's density
  float step_size = 0.0f;   // metres; 0 = automatic (a voxel for grids, one step if homogeneous)
  float step_scale = 1.0f;  // multiplies the automatic step (bias against speed: docs/techniques.md)
  std::optional<BlackbodyEmission> blackbody;  // grid fields with a temperature channel
  std::optional<FlameEmission> flame;          // grid fields with a flame channel
  bool tint_with_color_grid = true;            // a grid's Cd (clamped to [0, 1]) tints sigma_s
  float holdout = 0.0f;  // holdout extinction sigma_h, 1/m at density 1 (MediumSample::holdout)
};

struct VolumePrimitive {
  VolumeShape shape;
  VolumeShader shader;  // the scene medium's, copied next to the shape for the hot loop
  int medium = -1;      // index into the scene's media table (-1: made in code)
};

// The ray's parametric overlap with the shape's convex hull (the mesh's bounding box for a
// mesh), clipped to [ray.tmin, ray.tmax]: where the primitive may have medium.
std::optional<RayRange> volume_hull_interval(const VolumeShape& shape, const Ray& ray);
// Appends the primitive's majorant intervals along the ray to context.intervals.
void append_intervals(const VolumePrimitive& primitive, uint32_t id, const Ray& ray, VolumeContext& context);
Bounds3 volume_bounds(const VolumeShape& shape);
// True when the coefficients are the same everywhere inside the shape (no field, no noise).
bool is_homogeneous(const VolumeShader& shader);
// True when the shader emits anywhere: a constant emission, a blackbody or a flame channel.
inline bool emits(const VolumeShader& s) { return !s.emission.is_black() || s.blackbody || s.flame; }
// The density field's multiplier at a world point inside the primitive (1 for constant
// fields; the shader's density and noise not included).
float field_density(const VolumePrimitive& primitive, Vec3 p, VolumeContext& context);
// Coefficients of the primitive at a world-space point inside it.
MediumSample shade_volume(const VolumePrimitive& primitive, Vec3 p, VolumeContext& context);
// World-space length of one voxel of a grid field (after its placement), else infinity.
float field_voxel_size(const VolumePrimitive& primitive);

}  // namespace caligo
