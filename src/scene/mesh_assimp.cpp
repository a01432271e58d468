// Stanford PLY and COLLADA through assimp (the caligo_assimp.so plugin), after our own checks of
// the PLY header and body, read first in a forked child.
#include "scene/mesh_reader.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <chrono>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "core/module_loader.h"
#include "grids/crash_probe.h"
#include "scene/assimp_plugin.h"

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

namespace caligo::mesh_detail {
namespace {

// ---- Stanford PLY and COLLADA (through assimp) ---------------------------------------------

// In an ASCII PLY, a list property starts with its length, and assimp allocates that many values
// before reading them: a face line "442949672954 0 1 2" cost 9 GB (found by fuzzing). assimp
// also reads the body as one stream of tokens, so a line with a token too few or too many shifts
// every later value (a coordinate then becomes a list length). Each body line is one element, in
// header order: it must hold numbers only, exactly as many as its properties say (a list counts
// its length and that many values; an element with more than one list must hold at least that).
struct PlyProperty {
  bool list = false;
  int count_bytes = 0;  // a list's length: its size in bytes
  int value_bytes = 0;  // a scalar's size, or each list value's (0: a type we do not know)
};
struct PlyElement {
  size_t count = 0;
  size_t scalars = 0, lists = 0;
  bool starts_with_list = false;
  std::vector<PlyProperty> properties;
};
struct PlyHeader {
  std::vector<PlyElement> elements;
  bool ascii = false, big_endian = false;
  int formats = 0;
  size_t declared = 0;  // elements declared so far, all kinds
  size_t lines = 0;     // header lines read
};

int ply_type_bytes(std::string_view type) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
  if (type == "int" || type == "uint" || type == "int32" || type == "uint32" || type == "float" || type == "float32")
    return 4;
  if (type == "double" || type == "float64") return 8;
  return 0;
}

// Names must read as names: assimp takes the digits that begin "5555vertex" as a number.
bool ply_name_ok(std::string_view w) {
  return !w.empty() && (std::isalpha(static_cast<unsigned char>(w[0])) || w[0] == '_') &&
         std::all_of(w.begin(), w.end(),
                     [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-'; });
}

// "element NAME COUNT": the count read, bounded by the mesh limits and by the file's size
// (readers reserve memory for it before reading; each element takes at least one byte).
void add_ply_element(std::string_view name, std::string_view count_text, size_t data_size, PlyHeader& h) {
  PlyElement e;
  const auto [end, ec] = std::from_chars(count_text.data(), count_text.data() + count_text.size(), e.count);
  if (ec != std::errc() || end != count_text.data() + count_text.size())
    fail("cannot parse PLY: element " + in_quotes(name) + " has the count " + in_quotes(count_text));
  const bool vertices = name == "vertex", faces = name == "face";
  if ((vertices && e.count > kMaxMeshVertices) || (faces && e.count > kMaxMeshTriangles))
    fail("the PLY header declares " + std::string(count_text) + " " + printable_for_message(name) +
         " elements; meshes are limited to " +
         (vertices ? std::to_string(kMaxMeshVertices) + " vertices" : std::to_string(kMaxMeshTriangles) + " triangles"));
  if (e.count > data_size || h.declared + e.count > data_size)
    fail("the PLY header declares " + std::string(count_text) + " " + printable_for_message(name) +
         " elements, more than the file's " + std::to_string(data_size) + " bytes can hold");
  h.declared += e.count;
  h.elements.push_back(e);
}

// One header line (its first five words). The header must be one assimp reads the way we do: one
// format, known types (a header with two format lines made assimp corrupt its heap); other
// unknown lines are skipped, as assimp does (Blender 2.47 wrote its credit line without "comment").
void read_ply_header_line(const std::array<std::string_view, 5>& words, size_t count, size_t data_size,
                          PlyHeader& h) {
  const auto header_error = [&](const std::string& what) {
    fail("cannot parse PLY: header line " + std::to_string(h.lines) + ": " + what);
  };
  if (h.lines == 1) {
    if (words[0] != "ply" || count != 1) header_error("expected \"ply\"");
    return;
  }
  if (words[0] == "format") {
    if (h.formats++ > 0) header_error("a second format line");
    if (count < 3 || (words[1] != "ascii" && words[1] != "binary_little_endian" && words[1] != "binary_big_endian"))
      header_error("expected \"format ascii|binary_little_endian|binary_big_endian 1.0\"");
    h.ascii = words[1] == "ascii";
    h.big_endian = words[1] == "binary_big_endian";
  } else if (words[0] == "element") {
    if (count < 3 || !ply_name_ok(words[1])) header_error("expected \"element NAME COUNT\" with a name of letters, digits and _");
    add_ply_element(words[1], words[2], data_size, h);
  } else if (words[0] == "property") {
    if (h.elements.empty()) header_error("a property before any element");
    const bool list = count >= 2 && words[1] == "list";
    if (!ply_name_ok(list ? words[4] : words[2])) header_error("a property name must be letters, digits and _");
    if (list ? (count < 5 || ply_type_bytes(words[2]) == 0 || ply_type_bytes(words[3]) == 0)
             : (count < 3 || ply_type_bytes(words[1]) == 0))
      header_error("expected \"property TYPE NAME\" or \"property list COUNT_TYPE TYPE NAME\" with known types");
    PlyElement& e = h.elements.back();
    if (e.scalars + e.lists == 0) e.starts_with_list = list;
    ++(list ? e.lists : e.scalars);
    // "property list COUNT VALUE name" or "property TYPE name".
    e.properties.push_back(list ? PlyProperty{true, ply_type_bytes(words[2]), ply_type_bytes(words[3])}
                                : PlyProperty{false, 0, ply_type_bytes(words[1])});
  }
}

PlyHeader read_ply_header(std::string_view text, size_t header_end, size_t data_size) {
  PlyHeader h;
  for (size_t start = 0; start < header_end;) {
    ++h.lines;
    const size_t newline = std::min(text.find('\n', start), header_end);
    std::array<std::string_view, 5> words;
    const size_t count = first_words(text.substr(start, newline - start), words);
    start = newline + 1;
    if (count == 0 || (h.lines > 1 && (words[0] == "comment" || words[0] == "obj_info"))) continue;
    read_ply_header_line(words, count, data_size, h);
  }
  if (h.formats == 0) fail("cannot parse PLY: no format line in the header");
  for (const PlyElement& e : h.elements)
    if (e.properties.empty() && e.count > 0) fail("cannot parse PLY: an element with no properties");
  return h;
}

// Binary: walk the elements, reading each list's length, so that no length promises more values
// than the file holds (assimp allocates them first: 24 GB for "list uint uint" with a length of
// 0x03000000, found by fuzzing).
void check_ply_binary_body(std::string_view text, size_t header_end, const PlyHeader& h) {
  size_t at = text.find('\n', header_end);
  if (at == std::string_view::npos) return;
  ++at;
  for (const PlyElement& e : h.elements)
    for (size_t i = 0; i < e.count; ++i)
      for (const PlyProperty& p : e.properties) {
        if (p.value_bytes == 0 || (p.list && p.count_bytes == 0)) return;  // an unknown type: assimp reports it
        if (!p.list) {
          at += size_t(p.value_bytes);
          continue;
        }
        if (p.count_bytes > 4 || at + size_t(p.count_bytes) > text.size())
          fail("cannot parse PLY: the data ends inside element " + std::to_string(i) + " of a list property");
        uint64_t length = 0;
        for (int b = 0; b < p.count_bytes; ++b) {
          const uint64_t byte = static_cast<unsigned char>(text[at + size_t(h.big_endian ? b : p.count_bytes - 1 - b)]);
          length = length << 8 | byte;
        }
        at += size_t(p.count_bytes);
        if (length > (text.size() - std::min(at, text.size())) / size_t(p.value_bytes))
          fail("cannot parse PLY: a list says it holds " + std::to_string(length) + " values, more than the " +
               std::to_string(text.size() - std::min(at, text.size())) + " bytes left in the file");
        at += size_t(length) * size_t(p.value_bytes);
      }
}

// One ASCII body line of element `e`: numbers only, as many as its properties say.
void check_ply_ascii_line(std::string_view line, const PlyElement& e, size_t line_number) {
  const auto line_error = [&](const std::string& what) { fail("PLY line " + std::to_string(line_number) + ": " + what); };
  size_t tokens = 0;
  bool in_token = false;
  for (char c : line) {
    const bool space = c == ' ' || c == '\t' || c == '\r';
    if (!space && !in_token) ++tokens;
    in_token = !space;
    if (!space && !(std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.' || c == 'e' ||
                    c == 'E'))
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

void check_ply_ascii_body(std::string_view text, size_t header_end, const PlyHeader& h) {
  size_t pos = text.find('\n', header_end);  // the end of the end_header line
  size_t line_number = h.lines + 2;  // after the header's lines and its end_header line
  for (const PlyElement& e : h.elements)
    for (size_t i = 0; i < e.count && pos != std::string_view::npos && pos + 1 < text.size(); ++i, ++line_number) {
      const size_t line_start = pos + 1;
      pos = text.find('\n', line_start);
      check_ply_ascii_line(text.substr(line_start, (pos == std::string_view::npos ? text.size() : pos) - line_start),
                           e, line_number);
    }
}

void check_ply_body(const std::string& data, size_t header_end) {
  const std::string_view text(data);
  const PlyHeader h = read_ply_header(text, header_end, data.size());
  if (h.ascii)
    check_ply_ascii_body(text, header_end, h);
  else
    check_ply_binary_body(text, header_end, h);
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

}  // namespace

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
                                                                   kAssimpPluginAbi, "needed to read PLY, COLLADA, STL and OFF meshes");
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

}  // namespace caligo::mesh_detail
