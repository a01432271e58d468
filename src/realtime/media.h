// The scene's volume primitives as the real-time passes see them: homogeneous primitives
// exactly (optical depth = sigma_t x overlap length, per interval), noise-modulated ones
// with their mean density for transmittance and a noise lookup for in-scattering.
//
// Grid and mesh volumes take the scalar path: their majorant intervals (empty blocks and the
// outside of a mesh skipped) integrated with Gauss-Legendre panels of two voxels.
//
// Approximations (documented in docs/techniques.md): the noise modulation multiplies
// density by 1 + a fbm with fbm zero-mean, so transmittance uses its mean factor 1; the
// in-scattering coefficient at a march sample uses the true noise lookup. Radial-falloff
// primitives integrate their density with 4-point Gauss-Legendre over each overlap (exact
// for sphere shapes with integer exponents <= 3: (1 - r^2)^e is then a polynomial of
// degree 2e <= 7 in t; otherwise an approximation, good to a few 1e-3 for smooth puffs).
// Height fog (HeightFalloffDensity) is integrated in closed form.
#pragma once

#include <span>

#include "core/ray.h"
#include "core/rgb.h"
#include "core/vec.h"
#include "volumes/volume_scene.h"

namespace caligo {

// True when the density field is constant over the shape's convex hull (noise aside): its mean
// density is then the shader's density everywhere, and transmittance through it is analytic.
bool has_constant_field(const VolumePrimitive& primitive);

// Density multiplier at a world point inside the primitive: shader density x field x noise.
float medium_density(const VolumePrimitive& primitive, Vec3 p);
// The same with the noise replaced by its mean factor 1 (what transmittance uses).
float mean_medium_density(const VolumePrimitive& primitive, Vec3 p);

// Optical depth (per channel, mean density) of one primitive over [t0, t1] of `ray`
// (t0, t1 inside the primitive's interval; unit direction).
RGB primitive_optical_depth(const VolumePrimitive& primitive, const Ray& ray, float t0, float t1);

// A primitive's shape as the SIMD passes test it, lane-parallel in object space: the
// world -> object affine rows and the object-space unit sphere or box [lo, hi].
struct ObjectSpaceShape {
  bool sphere = false;  // the unit sphere; else the box [lo, hi]
  float m[3][4];        // world -> object
  Vec3 lo, hi;
};
ObjectSpaceShape object_space_shape(const VolumeShape& shape);

// Optical depth (per channel, mean density) of one primitive along all of `ray`'s
// [tmin, tmax] (unit direction), over its majorant intervals.
RGB primitive_segment_optical_depth(const VolumePrimitive& primitive, const Ray& ray);

// The optical depth of one primitive from `ray`'s origin to each of `nodes` t values (increasing,
// from 0), added to `out` (nodes.size() entries): its majorant intervals found once.
void add_depth_profile(const VolumePrimitive& primitive, const Ray& ray, std::span<const float> nodes, RGB* out);

// Optical depth (per channel) of the straight segment from a to b.
RGB segment_optical_depth(const VolumeScene& volumes, Vec3 a, Vec3 b);

}  // namespace caligo
