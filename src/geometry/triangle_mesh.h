// An indexed triangle mesh in world space, as handed to Embree. Loaders and shape
// tessellation produce it; validate_mesh() is the gate every mesh passes before use.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/transform.h"
#include "core/vec.h"

namespace caligo {

struct TriangleMesh {
  std::vector<Vec3> positions;
  std::vector<uint32_t> indices;  // 3 per triangle
  std::vector<Vec3> normals;      // optional per-vertex shading normals (empty or one per position)
  std::vector<Vec2> uvs;          // optional per-vertex texture coordinates (empty or one per position)

  size_t triangle_count() const { return indices.size() / 3; }
};

// Applies an object-to-world transform to positions and normals; flips the winding when
// the transform mirrors, so geometric normals keep pointing outwards.
void transform_mesh(TriangleMesh& mesh, const Transform& object_to_world);

// True when the triangle has zero area (coincident or collinear vertices, tested in double).
bool is_degenerate_triangle(Vec3 p0, Vec3 p1, Vec3 p2);

// Removes zero-area triangles (and those repeating a vertex index); returns how many.
// Triangles with out-of-range indices are kept for validate_mesh() to report.
size_t remove_degenerate_triangles(TriangleMesh& mesh);

// Returns an empty string when the mesh is usable, otherwise the first problem found, e.g.
// "vertex 12 has a non-finite coordinate", "triangle 3 refers to vertex 99, but the mesh has 40 vertices",
// "triangle 7 is degenerate (zero area)", "mesh has no triangles".
std::string validate_mesh(const TriangleMesh& mesh);

}  // namespace caligo
