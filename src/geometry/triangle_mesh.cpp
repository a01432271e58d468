#include "geometry/triangle_mesh.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace caligo {

namespace {

// A triangle counts as degenerate when sin(angle between its edges) is below this. It is far
// below anything float coordinates can resolve (~1e-7), so it only catches triangles whose
// vertices are collinear or coincident, which Embree never hits and whose area is zero.
constexpr double kDegenerateSine = 1e-12;

std::string vertex_error(size_t v) { return "vertex " + std::to_string(v) + " has a non-finite coordinate"; }

std::string triangle_error(size_t t, const std::string& what) {
  return "triangle " + std::to_string(t) + " " + what;
}

std::string check_positions(const TriangleMesh& mesh) {
  for (size_t v = 0; v < mesh.positions.size(); ++v)
    if (!is_finite(mesh.positions[v])) return vertex_error(v);
  return {};
}

std::string check_uvs(const TriangleMesh& mesh) {
  if (mesh.uvs.empty()) return {};
  if (mesh.uvs.size() != mesh.positions.size())
    return "mesh has " + std::to_string(mesh.uvs.size()) + " texture coordinates for " +
           std::to_string(mesh.positions.size()) + " vertices";
  for (size_t v = 0; v < mesh.uvs.size(); ++v)
    if (!std::isfinite(mesh.uvs[v].x) || !std::isfinite(mesh.uvs[v].y))
      return "texture coordinate " + std::to_string(v) + " is not finite";
  return {};
}

std::string check_normals(const TriangleMesh& mesh) {
  if (mesh.normals.empty()) return {};
  if (mesh.normals.size() != mesh.positions.size())
    return "mesh has " + std::to_string(mesh.normals.size()) + " normals for " +
           std::to_string(mesh.positions.size()) + " vertices (needs none or one per vertex)";
  for (size_t v = 0; v < mesh.normals.size(); ++v)
    if (!is_finite(mesh.normals[v])) return "normal " + std::to_string(v) + " has a non-finite coordinate";
  return {};
}

}  // namespace

// Computed in double so that rounding in the cross product cannot hide exact collinearity.
bool is_degenerate_triangle(Vec3 p0, Vec3 p1, Vec3 p2) {
  const double e1[3] = {double(p1.x) - p0.x, double(p1.y) - p0.y, double(p1.z) - p0.z};
  const double e2[3] = {double(p2.x) - p0.x, double(p2.y) - p0.y, double(p2.z) - p0.z};
  const double c[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                       e1[0] * e2[1] - e1[1] * e2[0]};
  const double cross_len = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
  const double len1 = std::sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
  const double len2 = std::sqrt(e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2]);
  return cross_len <= kDegenerateSine * len1 * len2;
}

size_t remove_degenerate_triangles(TriangleMesh& mesh) {
  if (mesh.indices.size() % 3 != 0) return 0;  // validate_mesh() reports this
  const size_t n = mesh.positions.size();
  const auto keep = [&](const uint32_t* tri) {
    if (tri[0] >= n || tri[1] >= n || tri[2] >= n) return true;
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) return false;
    return !is_degenerate_triangle(mesh.positions[tri[0]], mesh.positions[tri[1]], mesh.positions[tri[2]]);
  };
  size_t kept = 0;
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    if (!keep(&mesh.indices[3 * t])) continue;
    std::copy_n(mesh.indices.begin() + std::ptrdiff_t(3 * t), 3,
                mesh.indices.begin() + std::ptrdiff_t(3 * kept));
    ++kept;
  }
  const size_t removed = mesh.triangle_count() - kept;
  mesh.indices.resize(3 * kept);
  return removed;
}

namespace {

std::string check_triangle(const TriangleMesh& mesh, size_t t) {
  const uint32_t* tri = &mesh.indices[3 * t];
  for (int k = 0; k < 3; ++k)
    if (tri[k] >= mesh.positions.size())
      return triangle_error(t, "refers to vertex " + std::to_string(tri[k]) + ", but the mesh has " +
                                   std::to_string(mesh.positions.size()) + " vertices");
  if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] ||
      is_degenerate_triangle(mesh.positions[tri[0]], mesh.positions[tri[1]], mesh.positions[tri[2]]))
    return triangle_error(t, "is degenerate (zero area)");
  return {};
}

}  // namespace

void transform_mesh(TriangleMesh& mesh, const Transform& object_to_world) {
  for (Vec3& p : mesh.positions) p = object_to_world.point(p);
  for (Vec3& n : mesh.normals) {
    const Vec3 m = object_to_world.normal(n);
    // A zero normal stays zero rather than turning into NaN; validation reports what it finds.
    n = length_squared(m) > 0.0f ? normalize(m) : m;
  }
  // A mirror reverses the sign of cross(p1 - p0, p2 - p0) relative to the transformed normals;
  // swapping two vertices per triangle restores the outward-facing geometric normal.
  if (object_to_world.swaps_handedness())
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3)
      std::swap(mesh.indices[i + 1], mesh.indices[i + 2]);
}

std::string validate_mesh(const TriangleMesh& mesh) {
  if (mesh.indices.size() % 3 != 0)
    return "mesh has " + std::to_string(mesh.indices.size()) + " indices, which is not a multiple of 3";
  if (mesh.indices.empty()) return "mesh has no triangles";
  // Embree silently drops primitives with NaN/Inf vertices, so they must be rejected here.
  if (std::string error = check_positions(mesh); !error.empty()) return error;
  if (std::string error = check_normals(mesh); !error.empty()) return error;
  if (std::string error = check_uvs(mesh); !error.empty()) return error;
  for (size_t t = 0; t < mesh.triangle_count(); ++t)
    if (std::string error = check_triangle(mesh, t); !error.empty()) return error;
  return {};
}

}  // namespace caligo
