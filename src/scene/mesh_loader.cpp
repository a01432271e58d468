#include "scene/mesh_loader.h"

// Debian ships the libraries compiled: include the declarations only (no *_IMPLEMENTATION).
// assimp is reached through the caligo_assimp.so plugin (assimp_plugin.h).
#include <tiny_gltf.h>
#include <tiny_obj_loader.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "core/module_loader.h"
#include "grids/crash_probe.h"

// ASan (gcc: __SANITIZE_ADDRESS__, clang: __has_feature) reserves terabytes of address space, so
// a child process under it cannot have its address space capped.
#if defined(__SANITIZE_ADDRESS__)
#define CALIGO_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define CALIGO_ASAN 1
#endif
#endif
#ifdef CALIGO_ASAN
constexpr bool kAddressSanitizer = true;
#else
constexpr bool kAddressSanitizer = false;
#endif
#include "scene/assimp_plugin.h"
#include "scene/mesh_text_scan.h"

namespace caligo {
namespace {

// Raised by the readers below with a bare message; load_mesh() adds the location and path.
class MeshFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

[[noreturn]] void fail(const std::string& what) { throw MeshFileError(what); }

// User text in messages: escaped and abbreviated (core/message_text.h).
std::string in_quotes(std::string_view s) { return quote_for_message(s); }
std::string path_in_quotes(std::string_view path) { return quote_for_message(path, kMessageFileBytes); }

// The libraries end their messages with newlines (and sometimes hold several lines).
std::string tidy_library_message(std::string message) {
  std::replace(message.begin(), message.end(), '\n', ' ');
  while (!message.empty() && std::isspace(static_cast<unsigned char>(message.back()))) message.pop_back();
  return message.empty() ? "unknown error" : message;
}

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

// ---- Assembling the result -----------------------------------------------------------------

// Concatenates the parts of a file into one mesh. Shading normals survive only when every part
// has them: a mesh cannot carry normals for some vertices and not others.
class MeshBuilder {
 public:
  void append(const TriangleMesh& part) {
    const size_t base = mesh_.positions.size();
    if (base + part.positions.size() > std::numeric_limits<uint32_t>::max())
      fail("the mesh has more vertices than 32-bit indices can address");
    all_parts_have_normals_ = all_parts_have_normals_ && !part.normals.empty();
    mesh_.positions.insert(mesh_.positions.end(), part.positions.begin(), part.positions.end());
    if (all_parts_have_normals_)
      mesh_.normals.insert(mesh_.normals.end(), part.normals.begin(), part.normals.end());
    for (uint32_t i : part.indices) mesh_.indices.push_back(static_cast<uint32_t>(base + i));
  }

  TriangleMesh finish() {
    if (!all_parts_have_normals_) mesh_.normals.clear();
    return std::move(mesh_);
  }

 private:
  TriangleMesh mesh_;
  bool all_parts_have_normals_ = true;
};

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

// ---- Wavefront OBJ -------------------------------------------------------------------------

// tinyobjloader reads "nan", "inf" and unreadable text as 0 without a word, which would silently
// move vertices. (Numbers too large for a float come out as infinity, which validate_mesh()
// rejects, so out-of-range values need no check here.)
void check_obj_number(std::string_view token, size_t line, const char* kind) {
  std::string_view digits = token;
  if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);  // from_chars rejects '+'
  double value = 0.0;
  const std::errc ec = std::from_chars(digits.data(), digits.data() + digits.size(), value).ec;
  const std::string prefix = "line " + std::to_string(line) + ": ";
  if (ec == std::errc::invalid_argument) fail(prefix + "cannot read the coordinate " + in_quotes(token));
  if (ec == std::errc() && !std::isfinite(value))
    fail(prefix + kind + " has a non-finite coordinate " + in_quotes(token));
}

// The first `N` whitespace-separated words of a line (fewer if the line is shorter).
template <size_t N>
size_t first_words(std::string_view line, std::array<std::string_view, N>& words) {
  size_t count = 0, pos = 0;
  while (count < N) {
    pos = line.find_first_not_of(" \t\r", pos);
    if (pos == std::string_view::npos) break;
    const size_t end = std::min(line.find_first_of(" \t\r", pos), line.size());
    words[count++] = line.substr(pos, end - pos);
    pos = end;
  }
  return count;
}

// What the first pass over an OBJ file counts: the elements that face indices refer to, and
// which normals are zero (a zero normal cannot be normalised; shading with it gives NaN).
struct ObjCounts {
  int64_t vertices = 0, texcoords = 0, normals = 0;
  std::vector<bool> zero_normal;  // per "vn" line
};

std::string obj_line(size_t line) { return "line " + std::to_string(line) + ": "; }

// Calls `visit(line_number, words)` for every line with the first `N` words of the line.
template <size_t N, typename Visit>
void for_each_obj_line(std::string_view text, Visit&& visit) {
  size_t line_number = 0;
  for (size_t start = 0; start < text.size();) {
    const size_t newline = std::min(text.find('\n', start), text.size());
    const std::string_view line = text.substr(start, newline - start);
    start = newline + 1;
    ++line_number;
    std::array<std::string_view, N> words;
    const size_t count = first_words(line, words);
    if (count > 0) visit(line_number, line, words, count);
  }
}

// Counts the elements and checks the first three numbers of every position ("v") and normal
// ("vn") line.
ObjCounts count_obj_elements(std::string_view text) {
  ObjCounts counts;
  for_each_obj_line<4>(text, [&](size_t line, std::string_view, const auto& words, size_t count) {
    if (words[0] == "vt") ++counts.texcoords;
    if (words[0] != "v" && words[0] != "vn") return;
    if (count < 4) fail(obj_line(line) + std::string(words[0]) + " needs three coordinates");
    bool zero = true;
    for (size_t i = 1; i <= 3; ++i) {
      check_obj_number(words[i], line, words[0] == "v" ? "vertex" : "normal");
      double value = 0.0;
      std::string_view digits = words[i];
      if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
      std::from_chars(digits.data(), digits.data() + digits.size(), value);
      zero = zero && float(value) == 0.0f;
    }
    if (words[0] == "v") {
      ++counts.vertices;
    } else {
      ++counts.normals;
      counts.zero_normal.push_back(zero);
    }
  });
  if (counts.vertices > int64_t(kMaxMeshVertices))
    fail("the file has " + std::to_string(counts.vertices) + " vertices; meshes are limited to " +
         std::to_string(kMaxMeshVertices));
  return counts;
}

struct ObjIndexKind {
  const char* singular;
  const char* plural;
};
constexpr ObjIndexKind kObjVertex{"vertex", "vertices"};
constexpr ObjIndexKind kObjTexcoord{"texture coordinate", "texture coordinates"};
constexpr ObjIndexKind kObjNormal{"normal", "normals"};

// One index of a face corner (its "v", "vt" or "vn" part): a number from 1 to `total`, or a
// negative one counting back from the `seen` elements defined above the face. Returns the
// 0-based index. tinyobjloader reads indices with atoi (10^20 becomes -1, the last vertex)
// and leaves ranges to the caller, so every index is checked here, with its line.
int64_t obj_index(std::string_view token, ObjIndexKind kind, int64_t seen, int64_t total, size_t line) {
  int64_t value = 0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec == std::errc::invalid_argument || end != token.data() + token.size())
    fail(obj_line(line) + "cannot read the " + kind.singular + " index " + quote_for_message(token));
  const std::string refers =
      obj_line(line) + "a face refers to " + kind.singular + " " + printable_for_message(token);
  if (ec == std::errc::result_out_of_range || value > total)
    fail(refers + ", but the file has " + std::to_string(total) + " " + kind.plural);
  if (value == 0) fail(refers + " (OBJ counts from 1)");
  if (value < 0 && -value > seen)
    fail(refers + " (relative), but only " + std::to_string(seen) + " " + kind.plural + " precede the face");
  return value > 0 ? value - 1 : seen + value;
}

// Checks every face ("f") line: at least 3 corners (a face with fewer is degenerate: an
// error, or skipped with "skip_degenerate"), every index in range, no zero normal used, and
// at most kMaxMeshTriangles triangles after triangulation.
void check_obj_faces_text(std::string_view text, const ObjCounts& counts, DegenerateTriangles degenerate) {
  ObjCounts seen;
  uint64_t triangles = 0;
  for_each_obj_line<1>(text, [&](size_t line, std::string_view whole, const auto& words, size_t) {
    if (words[0] == "v") ++seen.vertices;
    if (words[0] == "vt") ++seen.texcoords;
    if (words[0] == "vn") ++seen.normals;
    if (words[0] != "f") return;
    size_t corners = 0;
    for (size_t pos = whole.find('f') + 1;;) {
      pos = whole.find_first_not_of(" \t\r", pos);
      if (pos == std::string_view::npos) break;
      const size_t end = std::min(whole.find_first_of(" \t\r", pos), whole.size());
      const std::string_view corner = whole.substr(pos, end - pos);
      pos = end;
      ++corners;
      const size_t slash1 = corner.find('/');
      const size_t slash2 = slash1 == std::string_view::npos ? slash1 : corner.find('/', slash1 + 1);
      obj_index(corner.substr(0, slash1), kObjVertex, seen.vertices, counts.vertices, line);
      if (slash1 == std::string_view::npos) continue;
      const size_t vt_length = slash2 == std::string_view::npos ? slash2 : slash2 - slash1 - 1;
      const std::string_view vt = corner.substr(slash1 + 1, vt_length);
      if (!vt.empty()) obj_index(vt, kObjTexcoord, seen.texcoords, counts.texcoords, line);
      if (slash2 == std::string_view::npos) continue;
      const int64_t n = obj_index(corner.substr(slash2 + 1), kObjNormal, seen.normals, counts.normals, line);
      if (counts.zero_normal[size_t(n)] && degenerate == DegenerateTriangles::kReject)
        fail(obj_line(line) + "a face uses normal " + std::to_string(n + 1) +
             ", which has zero length (a shading normal needs a direction; \"skip_degenerate\": true "
             "accepts it on faces it removes)");
    }
    if (corners < 3 && degenerate == DegenerateTriangles::kReject)
      fail(obj_line(line) + "a face has " + std::to_string(corners) +
           " vertices; a face needs at least 3 (\"skip_degenerate\": true drops such faces)");
    if (corners >= 3) triangles += corners - 2;
  });
  if (triangles > kMaxMeshTriangles)
    fail("the file has " + std::to_string(triangles) + " triangles; meshes are limited to " +
         std::to_string(kMaxMeshTriangles));
}

void check_obj_faces(const tinyobj::attrib_t& attrib, const std::vector<tinyobj::shape_t>& shapes) {
  const size_t vertex_count = attrib.vertices.size() / 3;
  const size_t normal_count = attrib.normals.size() / 3;
  for (const tinyobj::shape_t& shape : shapes) {
    for (unsigned int corners : shape.mesh.num_face_vertices)
      if (corners != 3) fail("a face has " + std::to_string(corners) + " vertices after triangulation");
    // tinyobjloader only warns about indices out of range; OBJ counts from 1.
    for (const tinyobj::index_t& index : shape.mesh.indices) {
      if (index.vertex_index < 0 || size_t(index.vertex_index) >= vertex_count)
        fail("a face refers to vertex " + std::to_string(int64_t(index.vertex_index) + 1) +
             ", but the file has " + std::to_string(vertex_count) + " vertices");
      if (index.normal_index >= 0 && size_t(index.normal_index) >= normal_count)
        fail("a face refers to normal " + std::to_string(int64_t(index.normal_index) + 1) +
             ", but the file has " + std::to_string(normal_count) + " normals");
    }
  }
}

bool every_corner_has_a_normal(const std::vector<tinyobj::shape_t>& shapes) {
  for (const tinyobj::shape_t& shape : shapes)
    for (const tinyobj::index_t& index : shape.mesh.indices)
      if (index.normal_index < 0) return false;
  return true;
}

Vec3 obj_vec3(const std::vector<tinyobj::real_t>& values, int index) {
  const size_t i = 3 * size_t(index);
  return {float(values[i]), float(values[i + 1]), float(values[i + 2])};
}

// Without normals the OBJ vertices map one to one onto mesh vertices.
TriangleMesh obj_mesh_without_normals(const tinyobj::attrib_t& attrib,
                                      const std::vector<tinyobj::shape_t>& shapes) {
  TriangleMesh mesh;
  const size_t vertex_count = attrib.vertices.size() / 3;
  mesh.positions.reserve(vertex_count);
  for (size_t v = 0; v < vertex_count; ++v) mesh.positions.push_back(obj_vec3(attrib.vertices, int(v)));
  for (const tinyobj::shape_t& shape : shapes)
    for (const tinyobj::index_t& index : shape.mesh.indices)
      mesh.indices.push_back(uint32_t(index.vertex_index));
  return mesh;
}

// OBJ indexes positions and normals separately; a mesh vertex is each distinct pair.
TriangleMesh obj_mesh_with_normals(const tinyobj::attrib_t& attrib,
                                   const std::vector<tinyobj::shape_t>& shapes) {
  TriangleMesh mesh;
  std::unordered_map<uint64_t, uint32_t> vertex_of_pair;
  for (const tinyobj::shape_t& shape : shapes)
    for (const tinyobj::index_t& index : shape.mesh.indices) {
      const uint64_t key = uint64_t(uint32_t(index.vertex_index)) << 32 | uint32_t(index.normal_index);
      const auto [it, added] = vertex_of_pair.try_emplace(key, uint32_t(mesh.positions.size()));
      if (added) {
        mesh.positions.push_back(obj_vec3(attrib.vertices, index.vertex_index));
        mesh.normals.push_back(obj_vec3(attrib.normals, index.normal_index));
      }
      mesh.indices.push_back(it->second);
    }
  return mesh;
}

TriangleMesh read_obj(const std::string& text, DegenerateTriangles degenerate) {
  check_obj_faces_text(text, count_obj_elements(text), degenerate);
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  // An empty material text keeps tinyobjloader from opening .mtl files we would not use.
  if (!reader.ParseFromString(text, "", config))
    fail("cannot parse OBJ: " + tidy_library_message(reader.Error()));
  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  const std::vector<tinyobj::shape_t>& shapes = reader.GetShapes();
  if (attrib.vertices.size() / 3 > std::numeric_limits<uint32_t>::max())
    fail("the mesh has more vertices than 32-bit indices can address");
  check_obj_faces(attrib, shapes);
  return !attrib.normals.empty() && every_corner_has_a_normal(shapes)
             ? obj_mesh_with_normals(attrib, shapes)
             : obj_mesh_without_normals(attrib, shapes);
}

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

bool is_affine_and_finite(const Mat4& m) {
  for (const auto& row : m.m)
    for (float v : row)
      if (!std::isfinite(v)) return false;
  return m.m[3][0] == 0.0f && m.m[3][1] == 0.0f && m.m[3][2] == 0.0f && m.m[3][3] == 1.0f;
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

// ---- Stanford PLY and COLLADA (through assimp) ---------------------------------------------

// In an ASCII PLY, a list property starts with its length, and assimp allocates that many values
// before reading them: a face line "442949672954 0 1 2" cost 9 GB (found by fuzzing). assimp
// also reads the body as one stream of tokens, so a line with a token too few or too many shifts
// every later value (a coordinate then becomes a list length). Each body line is one element, in
// header order: it must hold numbers only, exactly as many as its properties say (a list counts
// its length and that many values; an element with more than one list must hold at least that).
void check_ply_body(const std::string& data, size_t header_end) {
  struct Property {
    bool list = false;
    int count_bytes = 0;  // a list's length: its size in bytes
    int value_bytes = 0;  // a scalar's size, or each list value's (0: a type we do not know)
  };
  struct Element {
    size_t count = 0;
    size_t scalars = 0, lists = 0;
    bool starts_with_list = false;
    std::vector<Property> properties;
  };
  std::vector<Element> elements;
  bool ascii = false, big_endian = false;
  int formats = 0;
  size_t declared = 0;
  const auto type_bytes = [](std::string_view type) {
    if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
    if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
    if (type == "int" || type == "uint" || type == "int32" || type == "uint32" || type == "float" || type == "float32")
      return 4;
    if (type == "double" || type == "float64") return 8;
    return 0;
  };
  const std::string_view text(data);
  size_t line_number = 1;
  for (size_t start = 0; start < header_end; ++line_number) {
    const size_t newline = std::min(text.find('\n', start), header_end);
    std::array<std::string_view, 5> words;
    const size_t count = first_words(text.substr(start, newline - start), words);
    start = newline + 1;
    // The header must be one assimp reads the way we do: one format, known types (a header with
    // two format lines made assimp corrupt its heap); other unknown lines are skipped, as assimp does.
    const auto header_error = [&](const std::string& what) {
      fail("cannot parse PLY: header line " + std::to_string(line_number) + ": " + what);
    };
    if (count == 0) continue;
    if (line_number == 1) {
      if (words[0] != "ply" || count != 1) header_error("expected \"ply\"");
      continue;
    }
    if (words[0] == "comment" || words[0] == "obj_info") continue;
    if (words[0] == "format") {
      if (formats++ > 0) header_error("a second format line");
      if (count < 3 || (words[1] != "ascii" && words[1] != "binary_little_endian" && words[1] != "binary_big_endian"))
        header_error("expected \"format ascii|binary_little_endian|binary_big_endian 1.0\"");
      ascii = words[1] == "ascii";
      big_endian = words[1] == "binary_big_endian";
      continue;
    }
    // Names must read as names: assimp takes the digits that begin "5555vertex" as a number.
    const auto name_ok = [](std::string_view w) {
      return !w.empty() && (std::isalpha(static_cast<unsigned char>(w[0])) || w[0] == '_') &&
             std::all_of(w.begin(), w.end(), [](char c) {
               return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
             });
    };
    if (words[0] == "element" && (count < 3 || !name_ok(words[1])))
      header_error("expected \"element NAME COUNT\" with a name of letters, digits and _");
    if (words[0] == "property") {
      if (elements.empty()) header_error("a property before any element");
      const std::string_view name = count >= 2 && words[1] == "list" ? words[4] : words[2];
      if (!name_ok(name)) header_error("a property name must be letters, digits and _");
      const bool list = count >= 2 && words[1] == "list";
      if (list ? (count < 5 || type_bytes(words[2]) == 0 || type_bytes(words[3]) == 0)
               : (count < 3 || type_bytes(words[1]) == 0))
        header_error("expected \"property TYPE NAME\" or \"property list COUNT_TYPE TYPE NAME\" with known types");
    } else if (words[0] != "element") {
      continue;  // a line assimp skips too (Blender 2.47 wrote its credit line without "comment")
    }
    if (count >= 3 && words[0] == "element") {
      Element e;
      const auto [end, ec] = std::from_chars(words[2].data(), words[2].data() + words[2].size(), e.count);
      if (ec != std::errc() || end != words[2].data() + words[2].size())
        fail("cannot parse PLY: element " + in_quotes(words[1]) + " has the count " + in_quotes(words[2]));
      // Readers reserve memory for the declared counts before reading: each element takes at
      // least one byte (binary) or two characters (a value and a separator).
      const bool vertices = words[1] == "vertex", faces = words[1] == "face";
      if ((vertices && e.count > kMaxMeshVertices) || (faces && e.count > kMaxMeshTriangles))
        fail("the PLY header declares " + std::string(words[2]) + " " + printable_for_message(words[1]) +
             " elements; meshes are limited to " +
             (vertices ? std::to_string(kMaxMeshVertices) + " vertices"
                       : std::to_string(kMaxMeshTriangles) + " triangles"));
      if (e.count > data.size() || declared + e.count > data.size())
        fail("the PLY header declares " + std::string(words[2]) + " " + printable_for_message(words[1]) +
             " elements, more than the file's " + std::to_string(data.size()) + " bytes can hold");
      declared += e.count;
      elements.push_back(e);
    } else if (count >= 2 && words[0] == "property" && !elements.empty()) {
      Element& e = elements.back();
      const bool list = words[1] == "list";
      if (e.scalars + e.lists == 0) e.starts_with_list = list;
      ++(list ? e.lists : e.scalars);
      // "property list COUNT VALUE name" or "property TYPE name".
      e.properties.push_back(list ? Property{true, type_bytes(words[2]), type_bytes(words[3])}
                                  : Property{false, 0, type_bytes(words[1])});
    }
  }
  if (formats == 0) fail("cannot parse PLY: no format line in the header");
  for (const Element& e : elements)
    if (e.properties.empty() && e.count > 0) fail("cannot parse PLY: an element with no properties");
  if (!ascii) {
    // Binary: walk the elements, reading each list's length, so that no length promises more
    // values than the file holds (assimp allocates them first: 24 GB for "list uint uint" with a
    // length of 0x03000000, found by fuzzing).
    size_t at = text.find('\n', header_end);
    if (at == std::string_view::npos) return;
    ++at;
    for (const Element& e : elements)
      for (size_t i = 0; i < e.count; ++i)
        for (const Property& p : e.properties) {
          if (p.value_bytes == 0 || (p.list && p.count_bytes == 0)) return;  // an unknown type: assimp reports it
          if (!p.list) {
            at += size_t(p.value_bytes);
            continue;
          }
          if (p.count_bytes > 4 || at + size_t(p.count_bytes) > text.size())
            fail("cannot parse PLY: the data ends inside element " + std::to_string(i) + " of a list property");
          uint64_t length = 0;
          for (int b = 0; b < p.count_bytes; ++b) {
            const uint64_t byte = static_cast<unsigned char>(text[at + size_t(big_endian ? b : p.count_bytes - 1 - b)]);
            length = length << 8 | byte;
          }
          at += size_t(p.count_bytes);
          if (length > (text.size() - std::min(at, text.size())) / size_t(p.value_bytes))
            fail("cannot parse PLY: a list says it holds " + std::to_string(length) + " values, more than the " +
                 std::to_string(text.size() - std::min(at, text.size())) + " bytes left in the file");
          at += size_t(length) * size_t(p.value_bytes);
        }
    return;
  }
  size_t pos = text.find('\n', header_end);  // the end of the end_header line
  ++line_number;
  const auto line_error = [&](const std::string& what) { fail("PLY line " + std::to_string(line_number) + ": " + what); };
  for (const Element& e : elements)
    for (size_t i = 0; i < e.count && pos != std::string_view::npos && pos + 1 < text.size(); ++i, ++line_number) {
      const size_t line_start = pos + 1;
      pos = text.find('\n', line_start);
      const std::string_view line =
          text.substr(line_start, (pos == std::string_view::npos ? text.size() : pos) - line_start);
      size_t tokens = 0;
      bool in_token = false;
      for (char c : line) {
        const bool space = c == ' ' || c == '\t' || c == '\r';
        if (!space && !in_token) ++tokens;
        in_token = !space;
        if (!space && !(std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.' ||
                        c == 'e' || c == 'E'))
          line_error("expected numbers only, found " + quote_for_message(line.substr(0, 40)));
      }
      size_t expected = e.scalars + e.lists;  // each list at least its length
      if (e.starts_with_list && tokens > 0) {
        const size_t first = line.find_first_not_of(" \t\r");
        size_t length = 0;
        const auto [end, ec] = std::from_chars(line.data() + first, line.data() + line.size(), length);
        const std::string_view said = line.substr(first, size_t(end - (line.data() + first)));
        if (ec != std::errc() || length > tokens - 1)
          line_error("a list says it holds " + quote_for_message(said.empty() ? line.substr(first, 24) : said) +
                     " values, but the line has " + std::to_string(tokens - 1) + " after it");
        expected += length;
      }
      const bool exact = e.lists <= (e.starts_with_list ? 1u : 0u);
      if (exact ? tokens != expected : tokens < expected)
        line_error("expected " + std::to_string(expected) + " values for its element, found " + std::to_string(tokens));
    }
}

// Where the header's "end_header" LINE starts (blanks and a CR may follow it), as assimp finds
// it: "end_header" inside a comment does not end the header.
size_t ply_end_header_line(const std::string& data) {
  constexpr std::string_view kLine = "\nend_header";
  for (size_t at = data.find(kLine); at != std::string::npos; at = data.find(kLine, at + 1)) {
    size_t i = at + kLine.size();
    while (i < data.size() && (data[i] == ' ' || data[i] == '\t' || data[i] == '\r')) ++i;
    if (i < data.size() && data[i] == '\n') return at + 1;
  }
  return std::string::npos;
}

// Everything about a PLY file that assimp would trust: the header is text ending in an
// "end_header" line, then check_ply_body (counts, types, list lengths).
void check_ply_header(const std::string& data) {
  const size_t header_end = ply_end_header_line(data);
  if (data.compare(0, 3, "ply") != 0) fail("cannot parse PLY: no header (\"ply\" first, up to \"end_header\")");
  if (header_end == std::string::npos) fail("cannot parse PLY: the header does not end with an \"end_header\" line");
  // The header is text: bytes assimp's tokenizer reads in its own way (NUL, other controls,
  // bytes above 0x7e) made it corrupt its heap on fuzzed headers.
  // Comments may hold UTF-8 (an author's name): bytes above 0x7e are allowed there.
  bool in_comment = false;
  for (size_t i = 0; i < header_end; ++i) {
    const unsigned char c = static_cast<unsigned char>(data[i]);
    if (i == 0 || data[i - 1] == '\n')
      in_comment = data.compare(i, 8, "comment ") == 0 || data.compare(i, 9, "obj_info ") == 0;
    if ((c < 0x20 && c != '\n' && c != '\r' && c != '\t') || (c > 0x7e && !in_comment))
      fail("cannot parse PLY: the header holds a byte that is not text (0x" +
           std::string(1, "0123456789abcdef"[c >> 4]) + std::string(1, "0123456789abcdef"[c & 15]) + ") at offset " +
           std::to_string(i));
  }
  check_ply_body(data, header_end);
}

// aiMatrix4x4 is row-major with points as column vectors, like Mat4.
Mat4 to_mat4(const std::array<std::array<float, 4>, 4>& rows) {
  Mat4 m;
  m.m = rows;
  return m;
}

// One assimp mesh in its own space; points and lines (which PLY may hold) are not surfaces
// and are skipped, as is every mesh without triangles.
TriangleMesh assimp_part(const AssimpMeshCopy& mesh, unsigned mesh_index) {
  TriangleMesh part;
  part.positions = mesh.positions;
  part.normals = mesh.normals;
  const size_t vertex_count = mesh.positions.size();
  size_t next = 0;
  for (size_t f = 0; f < mesh.face_sizes.size(); ++f) {
    const uint32_t size = mesh.face_sizes[f];
    const uint32_t* corners = mesh.indices.data() + next;
    next += size;
    if (size < 3) continue;
    if (size != 3)
      fail("mesh " + std::to_string(mesh_index) + ", face " + std::to_string(f) + " has " + std::to_string(size) +
           " vertices after triangulation");
    for (unsigned k = 0; k < 3; ++k) {
      if (corners[k] >= vertex_count)
        fail("mesh " + std::to_string(mesh_index) + ", face " + std::to_string(f) + " refers to vertex " +
             std::to_string(corners[k]) + ", but it has " + std::to_string(vertex_count));
      part.indices.push_back(corners[k]);
    }
  }
  return part;
}

// Every mesh instance under the root node, with the node transforms applied (as for glTF).
TriangleMesh assimp_scene_mesh(const AssimpSceneCopy& scene) {
  struct Pending {
    uint32_t node;
    Mat4 parent;
  };
  std::vector<Pending> stack{{0, Mat4::identity()}};
  MeshBuilder builder;
  size_t visited = 0;
  while (!stack.empty()) {
    const Pending pending = stack.back();
    stack.pop_back();
    const AssimpNodeCopy& node = scene.nodes[pending.node];
    // The plugin bounds the copy too (kMaxAssimpNodes).
    if (++visited > kMaxAssimpNodes) fail("the file's node hierarchy is too large");
    const Mat4 node_to_model = pending.parent * to_mat4(node.transform);
    if (!is_affine_and_finite(node_to_model)) fail("a node has a non-affine or non-finite transform");
    const std::optional<Transform> transform = Transform::from_matrix(node_to_model);
    for (size_t i = 0; i < node.meshes.size() && transform; ++i) {
      const uint32_t index = node.meshes[i];
      if (index >= scene.meshes.size() || !scene.meshes[index].present) fail("a node refers to a missing mesh");
      TriangleMesh part = assimp_part(scene.meshes[index], index);
      if (part.indices.empty()) continue;  // points or lines only: nothing to add, not even normals
      if (!transform->is_identity()) transform_mesh(part, *transform);
      builder.append(part);
    }
    for (const uint32_t child : node.children) stack.push_back({child, node_to_model});
  }
  return builder.finish();
}

const AssimpPluginApi& assimp_plugin() {
  static const AssimpPluginApi& api = load_plugin<AssimpPluginApi>(kAssimpPluginName, kAssimpPluginSymbol,
                                                                   kAssimpPluginAbi, "needed to read PLY and COLLADA meshes");
  return api;
}

// Imported by the plugin (validate, triangulate, weld); `format` is assimp's extension hint.
TriangleMesh read_with_assimp(const std::string& data, const char* format, const char* name) {
  // assimp 5.2 corrupts its heap, loops or allocates without bound on some hostile PLY and
  // COLLADA files that pass every check above (each fuzzing run found another). So it reads the
  // file first in a forked child (grids/crash_probe.h, as OpenVDB does), under a time limit and
  // a memory cap, and in this process only when the child came through. About 1 ms per mesh.
  constexpr uint64_t kProbeMemory = kAddressSanitizer ? 0 : uint64_t(4) << 30;  // ASan reserves terabytes
  const ProbeOutcome probe = probe_in_child(
      [&] {
        AssimpSceneCopy trial;
        std::string ignored;
        assimp_plugin().read(data.data(), data.size(), format, &trial, &ignored);
      },
      std::chrono::seconds(20), kProbeMemory);
  if (probe.result == ProbeResult::kCrashed)
    fail(std::string("cannot parse ") + name + ": the reader (assimp) crashed on this file");
  if (probe.result == ProbeResult::kUnknown)
    fail(std::string("cannot parse ") + name + ": the reader (assimp) did not finish within 20 s");
  if (probe.result == ProbeResult::kThrew)
    fail(std::string("cannot parse ") + name + ": the reader (assimp) failed: " + tidy_library_message(probe.message));
  AssimpSceneCopy scene;
  std::string error;
  switch (assimp_plugin().read(data.data(), data.size(), format, &scene, &error)) {
    case AssimpReadStatus::kOk:
      break;
    case AssimpReadStatus::kCannotParse:
      fail(std::string("cannot parse ") + name + ": " + tidy_library_message(error));
    case AssimpReadStatus::kTooManyNodes:
      fail("the file's node hierarchy is too large");
  }
  if (scene.incomplete || scene.nodes.empty()) fail(std::string("the ") + name + " file holds no mesh");
  return assimp_scene_mesh(scene);
}

// ---- Clean-up -------------------------------------------------------------------------------

TriangleMesh read_mesh(const std::string& path, const SourceLocation& where, DegenerateTriangles degenerate) {
  const std::string extension = lowercase_extension(path);
  if (extension != ".obj" && extension != ".gltf" && extension != ".glb" && extension != ".ply" &&
      extension != ".dae")
    fail("unsupported mesh format " + in_quotes(extension) + " (expected .obj, .gltf, .glb, .ply or .dae)");
  const std::string data = read_whole_file(path, where);
  if (extension == ".obj") return read_obj(data, degenerate);
  if (extension == ".ply") {
    check_ply_header(data);
    return read_with_assimp(data, "ply", "PLY");
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
