// Mesh files (Wavefront OBJ, glTF 2.0 .gltf/.glb, Stanford PLY, COLLADA .dae, STL, OFF) -> one validated
// TriangleMesh. The parsing libraries (tinyobjloader, tinygltf, assimp for PLY and COLLADA)
// stay behind this header: only the readers (mesh_obj.cpp, mesh_gltf.cpp, mesh_assimp.cpp)
// compile against them.
#pragma once

#include <cstddef>
#include <string>

#include "core/error.h"
#include "geometry/triangle_mesh.h"

namespace caligo {

// Loads every triangle of the file at `path` into one mesh in the file's model space: all OBJ
// shapes, or every mesh instance of a glTF file's default scene (or of the scene assimp builds
// from a PLY or COLLADA file) with its node transforms applied; polygons are triangulated, and
// points and lines are skipped. Normals are kept only when every triangle has them. The result has passed
// validate_mesh(). Any problem throws InputError at `where` (the shape's place in the scene
// file) with a message naming `path`.
//
// Zero-area triangles are an error by default (a broken export should not render silently);
// many real files carry a few, so a scene may ask for them to be removed instead
// ("skip_degenerate": true on the mesh shape).
// The same rule covers OBJ faces with fewer than 3 corners: an error, or dropped on request.
enum class DegenerateTriangles { kReject, kRemove };

// The largest mesh a file may hold (docs/scene-format.md, "Limits"): about 10 GB of indices,
// positions and BVH. Counted before the bulk of the data is read where the format allows
// (OBJ lines, glTF accessor counts, PLY header counts).
inline constexpr size_t kMaxMeshTriangles = 100'000'000;
inline constexpr size_t kMaxMeshVertices = 100'000'000;
// Nesting limits for the text formats whose parsers recurse once per level (a few thousand
// levels overflow the stack): arrays and objects in a glTF's JSON (.gltf, or a GLB's JSON
// chunk), elements in a COLLADA file. Counted without recursion before the library parses.
inline constexpr size_t kMaxGltfJsonDepth = 128;
inline constexpr size_t kMaxColladaDepth = 256;
TriangleMesh load_mesh(const std::string& path, const SourceLocation& where,
                       DegenerateTriangles degenerate = DegenerateTriangles::kReject);

}  // namespace caligo
