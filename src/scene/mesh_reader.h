// What the mesh readers of scene/ share (mesh_loader.cpp, mesh_obj.cpp, mesh_gltf.cpp,
// mesh_assimp.cpp): their error type, message helpers, the builder that concatenates a file's
// parts, and each format's reader. Internal to mesh_io.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cctype>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>

#include "core/message_text.h"
#include "core/transform.h"
#include "geometry/triangle_mesh.h"
#include "scene/mesh_loader.h"

namespace caligo::mesh_detail {

// Raised by the readers with a bare message; load_mesh() adds the location and path.
class MeshFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

[[noreturn]] inline void fail(const std::string& what) { throw MeshFileError(what); }

// User text in messages: escaped and abbreviated (core/message_text.h).
inline std::string in_quotes(std::string_view s) { return quote_for_message(s); }
inline std::string path_in_quotes(std::string_view path) { return quote_for_message(path, kMessageFileBytes); }

// The libraries end their messages with newlines (and sometimes hold several lines).
inline std::string tidy_library_message(std::string message) {
  std::replace(message.begin(), message.end(), '\n', ' ');
  while (!message.empty() && std::isspace(static_cast<unsigned char>(message.back()))) message.pop_back();
  return message.empty() ? "unknown error" : message;
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

// The first `N` whitespace-separated words of a line (fewer if the line is shorter).
template <size_t N>
inline size_t first_words(std::string_view line, std::array<std::string_view, N>& words) {
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

inline bool is_affine_and_finite(const Mat4& m) {
  for (const auto& row : m.m)
    for (float v : row)
      if (!std::isfinite(v)) return false;
  return m.m[3][0] == 0.0f && m.m[3][1] == 0.0f && m.m[3][2] == 0.0f && m.m[3][3] == 1.0f;
}

// The formats' readers (each in its own file).
TriangleMesh read_obj(const std::string& text, DegenerateTriangles degenerate);  // mesh_obj.cpp
TriangleMesh read_gltf(const std::string& data, const std::string& path);       // mesh_gltf.cpp
// PLY's header and body checks before assimp reads it, and assimp's read (mesh_assimp.cpp).
void check_ply_header(const std::string& data);
// STL's and OFF's checks before assimp reads them (mesh_stl_off.cpp).
void check_stl(const std::string& data);
void check_off(const std::string& data);
TriangleMesh read_with_assimp(const std::string& data, const char* format, const char* name);

}  // namespace caligo::mesh_detail
