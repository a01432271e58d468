#include "scene/mesh_loader.h"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "scene/mesh_reader.h"
#include "scene/mesh_text_scan.h"

namespace caligo {
namespace {

using namespace mesh_detail;

std::string lowercase_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

std::string read_whole_file(const std::string& path, const SourceLocation& where) {
  std::error_code ec;
  std::ifstream in(path, std::ios::binary);
  if (!in || std::filesystem::is_directory(path, ec))
    throw InputError(where, "cannot open mesh file " + path_in_quotes(path));
  std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(where, "cannot read mesh file " + path_in_quotes(path));
  return data;
}

// A zero normal has no direction to shade with. Exports write them for zero-area faces, so
// they follow the degenerate-triangle rule: an error, unless "skip_degenerate" removed every
// triangle that uses one (checked after the removal; unused vertices do not matter).
void check_no_zero_normals(const TriangleMesh& mesh) {
  if (mesh.normals.empty()) return;
  for (size_t i = 0; i < mesh.indices.size(); ++i)
    if (!(length_squared(mesh.normals[mesh.indices[i]]) > 0.0f))
      fail("triangle " + std::to_string(i / 3) + " uses a zero-length normal (vertex " +
           std::to_string(mesh.indices[i]) + "); a shading normal needs a direction");
}

// Every format's result, whatever its loader counted on the way.
void check_mesh_limits(const TriangleMesh& mesh) {
  if (mesh.triangle_count() > kMaxMeshTriangles)
    fail("the mesh has " + std::to_string(mesh.triangle_count()) + " triangles; meshes are limited to " +
         std::to_string(kMaxMeshTriangles));
  if (mesh.positions.size() > kMaxMeshVertices)
    fail("the mesh has " + std::to_string(mesh.positions.size()) + " vertices; meshes are limited to " +
         std::to_string(kMaxMeshVertices));
}

// ---- Dispatch by format --------------------------------------------------------------------

TriangleMesh read_mesh(const std::string& path, const SourceLocation& where, DegenerateTriangles degenerate) {
  const std::string extension = lowercase_extension(path);
  if (extension != ".obj" && extension != ".gltf" && extension != ".glb" && extension != ".ply" &&
      extension != ".dae" && extension != ".stl" && extension != ".off")
    fail("unsupported mesh format " + in_quotes(extension) + " (expected .obj, .gltf, .glb, .ply, .dae, .stl or .off)");
  const std::string data = read_whole_file(path, where);
  if (extension == ".obj") return read_obj(data, degenerate);
  if (extension == ".ply") {
    check_ply_header(data);
    return read_with_assimp(data, "ply", "PLY");
  }
  if (extension == ".stl") {
    check_stl(data);
    // STL's normals are per facet (flat, as the geometric normal is) and often zero or stale
    // in exported files: the geometry alone decides.
    TriangleMesh mesh = read_with_assimp(data, "stl", "STL");
    mesh.normals.clear();
    return mesh;
  }
  if (extension == ".off") {
    check_off(data);
    return read_with_assimp(data, "off", "OFF");
  }
  if (extension == ".dae") {
    for (const std::string& problem : {collada_nesting_problem(data), collada_accessor_problem(data)})
      if (!problem.empty()) fail(problem);
    return read_with_assimp(data, "dae", "COLLADA");
  }
  return read_gltf(data, path);
}

}  // namespace

TriangleMesh load_mesh(const std::string& path, const SourceLocation& where, DegenerateTriangles degenerate) {
  try {
    TriangleMesh mesh = read_mesh(path, where, degenerate);
    if (degenerate == DegenerateTriangles::kRemove) {
      const size_t removed = remove_degenerate_triangles(mesh);
      if (mesh.indices.empty() && removed > 0)
        fail("all " + std::to_string(removed) + " triangles are degenerate (zero area)");
    }
    check_mesh_limits(mesh);
    if (const std::string problem = validate_mesh(mesh); !problem.empty()) fail(problem);
    check_no_zero_normals(mesh);
    return mesh;
  } catch (const MeshFileError& e) {
    throw InputError(where, printable_for_message(path, kMessageFileBytes) + ": " + e.what());
  }
}

}  // namespace caligo
