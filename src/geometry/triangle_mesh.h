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

  size_t triangle_count() const { return indices.size() / 3; }
};

// Applies an object-to-world transform to positions and normals; flips the winding when
// the transform mirrors, so geometric normals keep pointing outwards.
void transform_mesh(TriangleMesh& mesh, const Transform& object_to_world);

// Returns an empty string when the mesh is usable, otherwise the first problem found, e.g.
// "vertex 12 has a non-finite coordinate", "triangle 3 refers to vertex 99 (the mesh has 40)",
// "triangle 7 is degenerate (zero area)", "mesh has no triangles".
std::string validate_mesh(const TriangleMesh& mesh);

}  // namespace caligo
