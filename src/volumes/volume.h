// Volume primitives (the seed's "volume primitives": IOR 1, no boundary, additive overlap):
// a convex shape that turns a ray into an interval, plus a shader giving the medium's
// coefficients at a point. Closed sets are std::variants; add a shape or density field by
// extending the variant and the visitors in volume.cpp.
#pragma once

#include <optional>
#include <variant>

#include "core/ray.h"
#include "core/transform.h"
#include "geometry/shapes.h"
#include "media/medium.h"
#include "volumes/noise.h"

namespace caligo {

// A transformed axis-aligned box [lo, hi] (object space).
struct BoxVolumeShape {
  Transform object_to_world;
  Vec3 lo, hi;
};
struct SphereVolumeShape {
  Sphere sphere;
};
using VolumeShape = std::variant<SphereVolumeShape, BoxVolumeShape>;

// Density multipliers over the primitive, evaluated in its object space.
struct ConstantDensity {};
// 1 at the centre falling to 0 at the boundary of the unit sphere (object space):
// (1 - r^2)^exponent. A soft spherical puff; exercises heterogeneous marching.
struct RadialFalloffDensity {
  float exponent = 1.0f;
};
using DensityField = std::variant<ConstantDensity, RadialFalloffDensity>;

struct VolumeShader {
  RGB sigma_a;   // 1/m at density 1
  RGB sigma_s;   // 1/m at density 1
  RGB emission;  // W m^-3 sr^-1 at density 1
  float density = 1.0f;
  PhaseFunction phase;
  DensityField field;
  std::optional<NoiseModulation> noise;  // multiplies the field's density
  float step_size = 0.0f;  // metres; 0 = automatic (one step if homogeneous)
};

struct VolumePrimitive {
  VolumeShape shape;
  VolumeShader shader;
};

// The ray's parametric overlap with the shape, clipped to [ray.tmin, ray.tmax].
std::optional<std::pair<float, float>> volume_interval(const VolumeShape& shape, const Ray& ray);
Bounds3 volume_bounds(const VolumeShape& shape);
bool is_homogeneous(const VolumeShader& shader);
// The density field's multiplier at a world point inside the primitive (1 for constant
// fields; the shader's density and noise not included).
float field_density(const VolumePrimitive& primitive, Vec3 p);
// Coefficients of the primitive at a world-space point inside it.
MediumSample shade_volume(const VolumePrimitive& primitive, Vec3 p);
// Upper bound of sigma_t over the primitive (for delta tracking majorants).
RGB max_sigma_t(const VolumePrimitive& primitive);

}  // namespace caligo
