// Analytic and tessellated shape primitives. Boxes and rectangles become triangles;
// spheres stay analytic (an Embree user geometry) so they are exact and cheap, and the
// same intersection serves surfaces now and volume intervals later.
#pragma once

#include <optional>

#include "core/ray.h"
#include "core/ray_range.h"
#include "core/transform.h"
#include "geometry/triangle_mesh.h"

namespace caligo {

// Twelve outward-facing triangles of an axis-aligned box (before any transform).
TriangleMesh box_mesh(Vec3 min, Vec3 max);
// Two triangles of the parallelogram corner + s*edge1 + t*edge2, texture coordinates (s, t);
// normal along cross(edge1, edge2).
TriangleMesh rectangle_mesh(Vec3 corner, Vec3 edge1, Vec3 edge2);

// A sphere placed by an arbitrary affine transform of the unit sphere (so non-uniform
// scale gives an ellipsoid).
struct Sphere {
  Transform object_to_world;

  static Sphere make(Vec3 center, float radius, const Transform& placement);
  Bounds3 world_bounds() const { return object_to_world.bounds({Vec3(-1.0f), Vec3(1.0f)}); }
};

// Both roots of a ray against a sphere, in the ray's own parameter (not clipped to the
// ray's range): t0 <= t1 (core/ray_solids.h's sphere_roots in object space). std::nullopt when
// the ray misses.
std::optional<RayRange> intersect_sphere(const Sphere& sphere, const Ray& world_ray);
// Outward unit normal of the sphere at a world-space point on (or near) it.
Vec3 sphere_normal(const Sphere& sphere, Vec3 world_point);

}  // namespace caligo
