// caligo_assimp.so: the only code that calls assimp (see assimp_plugin.h).
#include "scene/assimp_plugin.h"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <exception>
#include <string_view>
#include <utility>

namespace caligo {
namespace {

AssimpMeshCopy copy_mesh(const aiMesh* mesh) {
  AssimpMeshCopy copy;
  if (mesh == nullptr) return copy;
  copy.present = true;
  copy.positions.reserve(mesh->mNumVertices);
  for (unsigned v = 0; v < mesh->mNumVertices; ++v)
    copy.positions.push_back({mesh->mVertices[v].x, mesh->mVertices[v].y, mesh->mVertices[v].z});
  if (mesh->mNormals != nullptr)
    for (unsigned v = 0; v < mesh->mNumVertices; ++v)
      copy.normals.push_back({mesh->mNormals[v].x, mesh->mNormals[v].y, mesh->mNormals[v].z});
  copy.face_sizes.reserve(mesh->mNumFaces);
  for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
    const aiFace& face = mesh->mFaces[f];
    copy.face_sizes.push_back(face.mNumIndices);
    copy.indices.insert(copy.indices.end(), face.mIndices, face.mIndices + face.mNumIndices);
  }
  return copy;
}

AssimpNodeCopy copy_node_fields(const aiNode& node) {
  const aiMatrix4x4& a = node.mTransformation;
  AssimpNodeCopy copy;
  copy.transform = {{{a.a1, a.a2, a.a3, a.a4}, {a.b1, a.b2, a.b3, a.b4}, {a.c1, a.c2, a.c3, a.c4},
                     {a.d1, a.d2, a.d3, a.d4}}};
  copy.meshes.assign(node.mMeshes, node.mMeshes + node.mNumMeshes);
  return copy;
}

// Breadth-first, so every child gets its index when its parent is copied.
bool copy_nodes(const aiNode& root, std::vector<AssimpNodeCopy>& nodes) {
  std::vector<const aiNode*> order{&root};
  nodes.push_back(copy_node_fields(root));
  for (size_t i = 0; i < order.size(); ++i) {
    for (unsigned c = 0; c < order[i]->mNumChildren; ++c) {
      const aiNode* child = order[i]->mChildren[c];
      if (child == nullptr) continue;
      if (order.size() >= kMaxAssimpNodes) return false;
      nodes[i].children.push_back(uint32_t(order.size()));
      order.push_back(child);
      nodes.push_back(copy_node_fields(*child));
    }
  }
  return true;
}

// A face without indices (a truncated binary PLY makes one) passes assimp's validation, marks
// its mesh as holding polygons, and the triangulation then asserts (aborting the process) on
// a "polygon" mesh without one. Such faces are refused and each mesh's primitive types are
// recomputed from its faces before triangulating. `scene` is the importer's own, not const.
bool has_empty_face_or_fix_types(const aiScene& scene) {
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    aiMesh* mesh = scene.mMeshes[m];
    if (mesh == nullptr) continue;
    unsigned types = 0;
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const unsigned n = mesh->mFaces[f].mNumIndices;
      if (n == 0) return true;
      types |= n == 1 ? aiPrimitiveType_POINT
               : n == 2 ? aiPrimitiveType_LINE
               : n == 3 ? aiPrimitiveType_TRIANGLE
                        : aiPrimitiveType_POLYGON;
    }
    mesh->mPrimitiveTypes = types;
  }
  return false;
}

// assimp 5.2's PLY reader runs past the end of its buffer (a crash) when no header line is
// "end_header" (the fuzzer's had "end_header*"): it keeps looking for one in the binary data.
// The PLY header ends with such a line; trailing blanks and a CR are allowed.
bool has_ply_end_header_line(std::string_view data) {
  constexpr std::string_view kLine = "\nend_header";
  for (size_t at = data.find(kLine); at != std::string_view::npos; at = data.find(kLine, at + 1)) {
    size_t i = at + kLine.size();
    while (i < data.size() && (data[i] == ' ' || data[i] == '\t' || data[i] == '\r')) ++i;
    if (i < data.size() && data[i] == '\n') return true;
  }
  return false;
}

// Triangulate and weld only: the other post-processing steps would change the geometry. The
// validation step comes first (with the reading): without it, a face that refers to a missing
// vertex crashes the triangulation.
AssimpReadStatus read(const char* data, size_t size, const char* format, AssimpSceneCopy* out, std::string* error) {
  if (std::string_view(format) == "ply" && !has_ply_end_header_line(std::string_view(data, size))) {
    *error = "the header does not end with an \"end_header\" line";
    return AssimpReadStatus::kCannotParse;
  }
  Assimp::Importer importer;
  const aiScene* scene = nullptr;
  try {
    scene = importer.ReadFileFromMemory(data, size, aiProcess_ValidateDataStructure, format);
    if (scene != nullptr && has_empty_face_or_fix_types(*scene)) {
      *error = "a face has no vertex indices (is the file truncated?)";
      return AssimpReadStatus::kCannotParse;
    }
    if (scene != nullptr) scene = importer.ApplyPostProcessing(aiProcess_Triangulate | aiProcess_JoinIdenticalVertices);
  } catch (const std::exception& e) {
    *error = e.what();
    return AssimpReadStatus::kCannotParse;
  }
  if (scene == nullptr) {
    *error = importer.GetErrorString();
    return AssimpReadStatus::kCannotParse;
  }
  if ((scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0 || scene->mRootNode == nullptr) {
    out->incomplete = true;
    return AssimpReadStatus::kOk;
  }
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) out->meshes.push_back(copy_mesh(scene->mMeshes[m]));
  return copy_nodes(*scene->mRootNode, out->nodes) ? AssimpReadStatus::kOk : AssimpReadStatus::kTooManyNodes;
}

}  // namespace
}  // namespace caligo

extern "C" __attribute__((visibility("default"))) const caligo::AssimpPluginApi* caligo_assimp_plugin() {
  static const caligo::AssimpPluginApi api{caligo::kAssimpPluginAbi, &caligo::read};
  return &api;
}
