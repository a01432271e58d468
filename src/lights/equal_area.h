// pbrt-v4's environment images: an equal-area square (Clarberg 2008, "Fast Equal-Area Mapping
// of the (Hemi)Sphere using SIMD"), the upper hemisphere (+z) in the inner diamond and the lower
// in the four corners, and their resampling into Caligo's latitude-longitude maps.
#pragma once

#include <vector>

#include "core/rgb.h"
#include "core/transform.h"
#include "core/vec.h"

namespace caligo {

// A unit direction to [0, 1]^2 and back; equal solid angles get equal areas.
Vec2 equal_area_sphere_to_square(Vec3 d);
Vec3 equal_area_square_to_sphere(Vec2 p);

// The lat-long map (environment_map.h's convention, `2n` x `n` pixels, Caligo's world) of an
// n x n equal-area image (row 0 at the top, x fastest, as image files are read) whose light
// space goes to the world by `light_to_world` (a rotation). Each output pixel is the bilinear
// lookup of its centre's direction.
std::vector<RGB> equal_area_to_latlong(const std::vector<RGB>& square, int n, const Transform& light_to_world);

}  // namespace caligo
