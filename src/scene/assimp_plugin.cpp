// caligo_assimp.so: the only code that calls assimp (see assimp_plugin.h).
#include "scene/assimp_plugin.h"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <exception>
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

// Triangulate and weld only: the other post-processing steps would change the geometry. The
// validation step comes first (assimp runs it before the others): without it, a face that
// refers to a missing vertex crashes the triangulation.
AssimpReadStatus read(const char* data, size_t size, const char* format, AssimpSceneCopy* out, std::string* error) {
  Assimp::Importer importer;
  const aiScene* scene = nullptr;
  constexpr unsigned kSteps =
      aiProcess_ValidateDataStructure | aiProcess_Triangulate | aiProcess_JoinIdenticalVertices;
  try {
    scene = importer.ReadFileFromMemory(data, size, kSteps, format);
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
