// The entry point of caligo_assimp.so, the plugin that keeps assimp (and its own zlib,
// minizip, poly2tri: ~2 ms and ~4 MB of process start-up) out of every run that reads no PLY or
// COLLADA mesh (see core/module_loader.h). The plugin only imports (validate, triangulate,
// weld) and copies assimp's scene into the plain structures below; mesh_assimp.cpp checks and
// flattens them. Host and plugin are built together, so C++ types cross the boundary;
// exceptions do not: failures come back as messages.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/vec.h"

namespace caligo {

struct AssimpMeshCopy {
  bool present = false;             // false: the scene's mesh pointer was null
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;        // empty when the mesh has none
  std::vector<uint32_t> face_sizes;  // indices per face (1: point, 2: line, 3: triangle, ...)
  std::vector<uint32_t> indices;     // every face's indices, one face after another
};

struct AssimpNodeCopy {
  std::array<std::array<float, 4>, 4> transform{};  // aiMatrix4x4 rows: points as column vectors
  std::vector<uint32_t> meshes;                     // indices into AssimpSceneCopy::meshes (unchecked)
  std::vector<uint32_t> children;                   // indices into AssimpSceneCopy::nodes
};

struct AssimpSceneCopy {
  bool incomplete = false;  // AI_SCENE_FLAGS_INCOMPLETE, or no root node
  std::vector<AssimpMeshCopy> meshes;
  std::vector<AssimpNodeCopy> nodes;  // nodes[0] is the root
};

// Nodes copied at most: assimp builds the tree itself, but a malformed file must not make the
// copy loop.
inline constexpr size_t kMaxAssimpNodes = 1'000'000;

enum class AssimpReadStatus { kOk, kCannotParse, kTooManyNodes };

struct AssimpPluginApi {
  int abi_version;
  // Imports `size` bytes with assimp's extension hint `format` ("ply", "dae"). kCannotParse
  // fills `error` with assimp's message (or the exception's).
  AssimpReadStatus (*read)(const char* data, size_t size, const char* format, AssimpSceneCopy* out,
                           std::string* error);
};

inline constexpr int kAssimpPluginAbi = 1;
inline constexpr const char* kAssimpPluginName = "caligo_assimp";
inline constexpr const char* kAssimpPluginSymbol = "caligo_assimp_plugin";

}  // namespace caligo
