// Closed triangle meshes made on demand, for occluders of a chosen size (the shadow-volume
// benchmarks need 20k to 750k triangles, more than the real meshes at hand provide) and for
// tests that need a closed, manifold surface with known geometry.
#pragma once

#include <cstdint>

#include "geometry/triangle_mesh.h"

namespace caligo {

// The unit sphere as a subdivided icosahedron: 20 * 4^subdivisions triangles, every vertex on
// the sphere, outward winding, closed and manifold (vertices shared). subdivisions in [0, 9].
TriangleMesh icosphere(int subdivisions);

// A (p, q) torus knot tube: the curve winds p times around the axis of symmetry and q times
// through the hole of a torus of radii `major` and `minor`; the tube of radius `tube` around
// it has `segments` rings of `sides` vertices (2 * segments * sides triangles, outward
// winding, closed). Requires p, q coprime >= 1, segments >= 3, sides >= 3.
struct TorusKnot {
  int p = 2, q = 3;
  float major = 1.0f, minor = 0.4f, tube = 0.15f;
  int segments = 256, sides = 16;
};
TriangleMesh torus_knot(const TorusKnot& knot);

// Subdivisions (sphere) or ring counts (knot, keeping segments = 16 * sides) whose triangle
// count is the smallest at or above `triangles` (at most 2^24).
int icosphere_subdivisions_for(uint64_t triangles);
TorusKnot torus_knot_for(uint64_t triangles);

}  // namespace caligo
