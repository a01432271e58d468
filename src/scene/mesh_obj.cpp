// Wavefront OBJ through tinyobjloader, after our own scan of the text (counts, indices, numbers).
#include "scene/mesh_reader.h"

// Debian ships the library compiled: include the declarations only (no *_IMPLEMENTATION).
#include <tiny_obj_loader.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace caligo::mesh_detail {
namespace {

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
      if (index.texcoord_index >= 0 && size_t(index.texcoord_index) >= attrib.texcoords.size() / 2)
        fail("a face refers to texture coordinate " + std::to_string(int64_t(index.texcoord_index) + 1) +
             ", but the file has " + std::to_string(attrib.texcoords.size() / 2) + " texture coordinates");
      if (index.normal_index >= 0 && size_t(index.normal_index) >= normal_count)
        fail("a face refers to normal " + std::to_string(int64_t(index.normal_index) + 1) +
             ", but the file has " + std::to_string(normal_count) + " normals");
    }
  }
}

bool every_corner_has(const std::vector<tinyobj::shape_t>& shapes, int tinyobj::index_t::*attribute) {
  for (const tinyobj::shape_t& shape : shapes)
    for (const tinyobj::index_t& index : shape.mesh.indices)
      if (index.*attribute < 0) return false;
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

}  // namespace

// OBJ indexes positions, texture coordinates and normals separately; a mesh vertex is each
// distinct triple of the attributes the mesh keeps (normals and uvs only where every corner has one).
TriangleMesh obj_mesh_with_attributes(const tinyobj::attrib_t& attrib, const std::vector<tinyobj::shape_t>& shapes,
                                      bool normals, bool uvs) {
  TriangleMesh mesh;
  struct KeyHash {
    size_t operator()(const std::array<int, 3>& k) const {
      return std::hash<uint64_t>()(uint64_t(uint32_t(k[0])) << 32 ^ uint64_t(uint32_t(k[1])) << 16 ^ uint32_t(k[2]));
    }
  };
  std::unordered_map<std::array<int, 3>, uint32_t, KeyHash> vertex_of;
  for (const tinyobj::shape_t& shape : shapes)
    for (const tinyobj::index_t& index : shape.mesh.indices) {
      const std::array<int, 3> key{index.vertex_index, normals ? index.normal_index : -1,
                                   uvs ? index.texcoord_index : -1};
      const auto [it, added] = vertex_of.try_emplace(key, uint32_t(mesh.positions.size()));
      if (added) {
        mesh.positions.push_back(obj_vec3(attrib.vertices, index.vertex_index));
        if (normals) mesh.normals.push_back(obj_vec3(attrib.normals, index.normal_index));
        if (uvs) {
          const size_t i = 2 * size_t(index.texcoord_index);
          mesh.uvs.push_back({float(attrib.texcoords[i]), float(attrib.texcoords[i + 1])});
        }
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
  const bool normals = !attrib.normals.empty() && every_corner_has(shapes, &tinyobj::index_t::normal_index);
  const bool uvs = !attrib.texcoords.empty() && every_corner_has(shapes, &tinyobj::index_t::texcoord_index);
  return normals || uvs ? obj_mesh_with_attributes(attrib, shapes, normals, uvs)
                        : obj_mesh_without_normals(attrib, shapes);
}

}  // namespace caligo::mesh_detail
