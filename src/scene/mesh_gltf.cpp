// glTF 2.0 (.gltf, .glb) through tinygltf: accessors checked against their buffers, primitives placed by the node hierarchy.
#include "scene/mesh_reader.h"

// Debian ships the library compiled: include the declarations only (no *_IMPLEMENTATION).
#include <tiny_gltf.h>

#include <filesystem>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <stdexcept>
#include <vector>

#include "scene/mesh_text_scan.h"

namespace caligo::mesh_detail {
namespace {

// ---- glTF 2.0: accessors -------------------------------------------------------------------

// Byte ranges of one accessor's elements, checked against the buffer: the file is untrusted
// and tinygltf does not check that accessors and buffer views stay inside their buffers.
struct AccessorBytes {
  const unsigned char* first = nullptr;
  size_t count = 0;
  size_t stride = 0;
};

std::string accessor_label(int index) { return "accessor " + std::to_string(index); }

const tinygltf::Accessor& find_accessor(const tinygltf::Model& model, int index) {
  if (index < 0 || size_t(index) >= model.accessors.size()) fail(accessor_label(index) + " does not exist");
  const tinygltf::Accessor& accessor = model.accessors[size_t(index)];
  if (accessor.sparse.isSparse) fail(accessor_label(index) + " is sparse, which is not supported");
  if (accessor.bufferView < 0 || size_t(accessor.bufferView) >= model.bufferViews.size())
    fail(accessor_label(index) + " has no buffer view (compressed data is not supported)");
  return accessor;
}

AccessorBytes accessor_bytes(const tinygltf::Model& model, int index, size_t element_size) {
  const tinygltf::Accessor& accessor = find_accessor(model, index);
  const tinygltf::BufferView& view = model.bufferViews[size_t(accessor.bufferView)];
  if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size())
    fail("buffer view " + std::to_string(accessor.bufferView) + " refers to a missing buffer");
  const std::vector<unsigned char>& buffer = model.buffers[size_t(view.buffer)].data;
  if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset)
    fail("buffer view " + std::to_string(accessor.bufferView) + " extends past the end of its buffer");
  const size_t stride = view.byteStride != 0 ? view.byteStride : element_size;
  if (stride < element_size) fail(accessor_label(index) + " has a byte stride smaller than its elements");
  if (accessor.count == 0) return {};
  // Written so that no product can overflow: (count - 1) * stride + element_size <= available.
  const size_t available = accessor.byteOffset <= view.byteLength ? view.byteLength - accessor.byteOffset : 0;
  if (available < element_size || (accessor.count - 1) > (available - element_size) / stride)
    fail(accessor_label(index) + " reads past the end of its buffer view");
  return {buffer.data() + view.byteOffset + accessor.byteOffset, accessor.count, stride};
}

std::vector<Vec3> read_vec3_accessor(const tinygltf::Model& model, int index, const std::string& attribute) {
  const tinygltf::Accessor& accessor = find_accessor(model, index);
  if (accessor.type != TINYGLTF_TYPE_VEC3 || accessor.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
    fail(attribute + " " + accessor_label(index) + " must hold 3-component float vectors");
  const AccessorBytes bytes = accessor_bytes(model, index, 3 * sizeof(float));
  std::vector<Vec3> values(bytes.count);
  for (size_t i = 0; i < bytes.count; ++i) {
    float xyz[3];
    std::memcpy(xyz, bytes.first + i * bytes.stride, sizeof xyz);  // the data may be unaligned
    values[i] = {xyz[0], xyz[1], xyz[2]};
  }
  return values;
}

template <typename Index>
void append_indices(const AccessorBytes& bytes, std::vector<uint32_t>& out) {
  for (size_t i = 0; i < bytes.count; ++i) {
    Index value;
    std::memcpy(&value, bytes.first + i * bytes.stride, sizeof value);
    out.push_back(value);
  }
}

std::vector<uint32_t> read_index_accessor(const tinygltf::Model& model, int index) {
  const tinygltf::Accessor& accessor = find_accessor(model, index);
  if (accessor.type != TINYGLTF_TYPE_SCALAR) fail("index " + accessor_label(index) + " must hold scalars");
  std::vector<uint32_t> indices;
  switch (accessor.componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      append_indices<uint8_t>(accessor_bytes(model, index, 1), indices);
      break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      append_indices<uint16_t>(accessor_bytes(model, index, 2), indices);
      break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      append_indices<uint32_t>(accessor_bytes(model, index, 4), indices);
      break;
    default:
      fail("index " + accessor_label(index) + " must hold unsigned 8, 16 or 32-bit integers");
  }
  return indices;
}

// ---- glTF 2.0: primitives and the node hierarchy ---------------------------------------------

std::string primitive_label(size_t mesh, size_t primitive) {
  return "mesh " + std::to_string(mesh) + ", primitive " + std::to_string(primitive);
}

std::vector<uint32_t> sequential_indices(size_t count) {
  std::vector<uint32_t> indices(count);
  for (size_t i = 0; i < count; ++i) indices[i] = uint32_t(i);
  return indices;
}

// Refuses a primitive over the mesh limits. Called after reading: its accessors have been
// checked against their buffers, so what was allocated is bounded by the file's size.
void check_gltf_counts(size_t vertices, size_t indices) {
  if (vertices > kMaxMeshVertices)
    fail("has " + std::to_string(vertices) + " vertices; meshes are limited to " +
         std::to_string(kMaxMeshVertices));
  if (indices / 3 > kMaxMeshTriangles)
    fail("has " + std::to_string(indices / 3) + " triangles; meshes are limited to " +
         std::to_string(kMaxMeshTriangles));
}

TriangleMesh read_primitive(const tinygltf::Model& model, size_t mesh_index, size_t primitive_index) {
  const tinygltf::Primitive& primitive = model.meshes[mesh_index].primitives[primitive_index];
  const std::string label = primitive_label(mesh_index, primitive_index);
  try {
    if (primitive.mode != TINYGLTF_MODE_TRIANGLES)
      fail("has mode " + std::to_string(primitive.mode) + "; only triangles (mode 4) are supported");
    const auto position = primitive.attributes.find("POSITION");
    if (position == primitive.attributes.end()) fail("has no POSITION attribute");
    TriangleMesh part;
    part.positions = read_vec3_accessor(model, position->second, "POSITION");
    if (part.positions.size() > std::numeric_limits<uint32_t>::max()) fail("has too many vertices");
    if (const auto normal = primitive.attributes.find("NORMAL"); normal != primitive.attributes.end()) {
      part.normals = read_vec3_accessor(model, normal->second, "NORMAL");
      if (part.normals.size() != part.positions.size())
        fail("has a different number of normals and positions");
    }
    part.indices = primitive.indices >= 0 ? read_index_accessor(model, primitive.indices)
                                          : sequential_indices(part.positions.size());
    check_gltf_counts(part.positions.size(), part.indices.size());
    if (part.indices.size() % 3 != 0)
      fail("has " + std::to_string(part.indices.size()) + " indices, which is not a multiple of 3");
    for (uint32_t i : part.indices)
      if (i >= part.positions.size())
        fail("refers to vertex " + std::to_string(i) + ", but it has " +
             std::to_string(part.positions.size()));
    return part;
  } catch (const MeshFileError& e) {
    fail(label + ": " + e.what());
  }
}

// glTF stores matrices column by column.
Mat4 column_major(const std::vector<double>& values) {
  Mat4 m;
  for (int column = 0; column < 4; ++column)
    for (int row = 0; row < 4; ++row) m.m[row][column] = float(values[size_t(4 * column + row)]);
  return m;
}

Mat4 translation_matrix(const std::vector<double>& t) {
  Mat4 m = Mat4::identity();
  for (int i = 0; i < 3; ++i) m.m[i][3] = float(t[size_t(i)]);
  return m;
}

Mat4 scale_matrix(const std::vector<double>& s) {
  Mat4 m = Mat4::identity();
  for (int i = 0; i < 3; ++i) m.m[i][i] = float(s[size_t(i)]);
  return m;
}

// Unit quaternion (x, y, z, w) to rotation matrix; normalised first, as exporters round.
Mat4 rotation_matrix(const std::vector<double>& q, const std::string& label) {
  const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (!(norm > 0.0) || !std::isfinite(norm)) fail(label + " has an invalid rotation quaternion");
  const double x = q[0] / norm, y = q[1] / norm, z = q[2] / norm, w = q[3] / norm;
  Mat4 m = Mat4::identity();
  m.m[0][0] = float(1 - 2 * (y * y + z * z));
  m.m[0][1] = float(2 * (x * y - z * w));
  m.m[0][2] = float(2 * (x * z + y * w));
  m.m[1][0] = float(2 * (x * y + z * w));
  m.m[1][1] = float(1 - 2 * (x * x + z * z));
  m.m[1][2] = float(2 * (y * z - x * w));
  m.m[2][0] = float(2 * (x * z - y * w));
  m.m[2][1] = float(2 * (y * z + x * w));
  m.m[2][2] = float(1 - 2 * (x * x + y * y));
  return m;
}

// The node's local transform: its matrix, or translation * rotation * scale.
Mat4 node_matrix(const tinygltf::Node& node, const std::string& label) {
  const auto size_ok = [](const std::vector<double>& v, size_t n) { return v.empty() || v.size() == n; };
  if (!size_ok(node.matrix, 16) || !size_ok(node.translation, 3) || !size_ok(node.rotation, 4) ||
      !size_ok(node.scale, 3))
    fail(label + " has a transform with the wrong number of values");
  Mat4 m = Mat4::identity();
  if (!node.matrix.empty()) {
    m = column_major(node.matrix);
  } else {
    if (!node.translation.empty()) m = m * translation_matrix(node.translation);
    if (!node.rotation.empty()) m = m * rotation_matrix(node.rotation, label);
    if (!node.scale.empty()) m = m * scale_matrix(node.scale);
  }
  if (!is_affine_and_finite(m)) fail(label + " has a non-affine or non-finite transform");
  return m;
}

// The roots of the scene to render: the default scene, else the first, else (a file without
// scenes) every node that is no other node's child.
std::vector<int> scene_roots(const tinygltf::Model& model) {
  if (!model.scenes.empty()) {
    const int scene = model.defaultScene >= 0 ? model.defaultScene : 0;
    if (size_t(scene) >= model.scenes.size())
      fail("the default scene " + std::to_string(scene) + " does not exist");
    return model.scenes[size_t(scene)].nodes;
  }
  std::vector<bool> is_child(model.nodes.size(), false);
  for (const tinygltf::Node& node : model.nodes)
    for (int child : node.children)
      if (child >= 0 && size_t(child) < model.nodes.size()) is_child[size_t(child)] = true;
  std::vector<int> roots;
  for (size_t n = 0; n < model.nodes.size(); ++n)
    if (!is_child[n]) roots.push_back(int(n));
  return roots;
}

struct MeshInstance {
  size_t mesh;
  Mat4 node_to_model;
};

// Walks the hierarchy depth-first without recursion (files may nest deeply), visiting each
// node at most once: glTF requires a tree, and a cycle or shared child would otherwise loop
// forever or multiply the work exponentially.
std::vector<MeshInstance> mesh_instances(const tinygltf::Model& model) {
  struct Pending {
    int node;
    Mat4 parent;
  };
  std::vector<Pending> stack;
  for (int root : scene_roots(model)) stack.push_back({root, Mat4::identity()});
  std::vector<bool> visited(model.nodes.size(), false);
  std::vector<MeshInstance> instances;
  while (!stack.empty()) {
    const Pending pending = stack.back();
    stack.pop_back();
    const std::string label = "node " + std::to_string(pending.node);
    if (pending.node < 0 || size_t(pending.node) >= model.nodes.size()) fail(label + " does not exist");
    if (visited[size_t(pending.node)]) fail(label + " appears more than once in the scene's node hierarchy");
    visited[size_t(pending.node)] = true;
    const tinygltf::Node& node = model.nodes[size_t(pending.node)];
    const Mat4 node_to_model = pending.parent * node_matrix(node, label);
    if (!is_affine_and_finite(node_to_model)) fail(label + " has a non-finite transform");
    if (node.mesh >= 0) {
      if (size_t(node.mesh) >= model.meshes.size()) fail(label + " refers to a missing mesh");
      instances.push_back({size_t(node.mesh), node_to_model});
    }
    for (int child : node.children) stack.push_back({child, node_to_model});
  }
  return instances;
}

// Extensions that change how geometry is stored; a file that requires one cannot be read
// correctly without it, and tinygltf does not decode any of them.
void check_required_extensions(const tinygltf::Model& model) {
  for (const std::string& extension : model.extensionsRequired) {
    const bool geometry_neutral = extension.rfind("KHR_materials_", 0) == 0 ||
                                  extension.rfind("KHR_texture_", 0) == 0 ||
                                  extension == "KHR_lights_punctual";
    if (!geometry_neutral) fail("the file requires the unsupported glTF extension " + extension);
  }
}

// Textures do not matter for geometry; skipping them avoids decoding (and trusting) images.
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int,
                void*) {
  return true;
}

}  // namespace

tinygltf::Model parse_gltf(const std::string& data, const std::string& path) {
  if (data.size() >= std::numeric_limits<unsigned int>::max()) fail("the file is too large (4 GiB or more)");
  if (const std::string problem = gltf_nesting_problem(data); !problem.empty()) fail(problem);
  tinygltf::TinyGLTF parser;
  parser.SetImageLoader(&skip_image, nullptr);
  // External buffers are found relative to the file.
  const std::string base_dir = std::filesystem::path(path).parent_path().string();
  const auto length = static_cast<unsigned int>(data.size());
  tinygltf::Model model;
  std::string error, warning;
  bool ok = false;
  try {
    // Recognise the binary container by its magic number rather than trusting the extension.
    ok = data.compare(0, 4, "glTF") == 0
             ? parser.LoadBinaryFromMemory(&model, &error, &warning,
                                           reinterpret_cast<const unsigned char*>(data.data()), length,
                                           base_dir)
             : parser.LoadASCIIFromString(&model, &error, &warning, data.data(), length, base_dir);
  } catch (const std::exception& e) {
    fail(std::string("cannot parse glTF: ") + e.what());
  }
  if (!ok) fail("cannot parse glTF: " + tidy_library_message(error));
  return model;
}

TriangleMesh read_gltf(const std::string& data, const std::string& path) {
  const tinygltf::Model model = parse_gltf(data, path);
  // tinygltf reads a glTF 1.0 file without complaint but finds nothing in it.
  if (model.asset.version.rfind("2.", 0) != 0)
    fail("glTF version " + in_quotes(model.asset.version) + " is not supported (only 2.x)");
  check_required_extensions(model);
  MeshBuilder builder;
  for (const MeshInstance& instance : mesh_instances(model)) {
    const std::optional<Transform> transform = Transform::from_matrix(instance.node_to_model);
    // A singular transform (a zero scale) is how glTF hides geometry: it has nothing to show.
    if (!transform) continue;
    for (size_t p = 0; p < model.meshes[instance.mesh].primitives.size(); ++p) {
      TriangleMesh part = read_primitive(model, instance.mesh, p);
      if (!transform->is_identity()) transform_mesh(part, *transform);
      builder.append(part);
    }
  }
  return builder.finish();
}

}  // namespace caligo::mesh_detail
