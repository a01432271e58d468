// STL (binary and ASCII) and OFF meshes: our own checks of what a file promises, before assimp
// reads it (mesh_assimp.cpp, in a forked child first). Effects and CAD tools export these two
// more than any other format; assimp reads both.
#include <charconv>
#include <cstdint>
#include <cstring>
#include <string_view>

#include "scene/mesh_reader.h"

namespace caligo::mesh_detail {
namespace {

// The byte at `i` as text for a message ("0x1f").
std::string hex_byte(unsigned char c) {
  constexpr const char* kDigits = "0123456789abcdef";
  return std::string("0x") + kDigits[c >> 4] + kDigits[c & 15];
}

// A text format holds no control bytes but tabs and line ends (assimp's tokenizers read NUL as
// the end of the buffer and other controls in their own ways).
void check_text(std::string_view data, const char* name) {
  for (size_t i = 0; i < data.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(data[i]);
    if (c < 0x20 && c != '\n' && c != '\r' && c != '\t')
      fail(std::string("cannot parse ") + name + ": a byte that is not text (" + hex_byte(c) + ") at offset " +
           std::to_string(i));
  }
}

std::string_view next_word(std::string_view text, size_t& pos) {
  // OFF allows comments from '#' to the end of the line.
  while (pos < text.size()) {
    if (text[pos] == '#') {
      pos = std::min(text.find('\n', pos), text.size());
    } else if (std::isspace(static_cast<unsigned char>(text[pos]))) {
      ++pos;
    } else {
      break;
    }
  }
  const size_t start = pos;
  while (pos < text.size() && !std::isspace(static_cast<unsigned char>(text[pos])) && text[pos] != '#') ++pos;
  return text.substr(start, pos - start);
}

size_t off_count(std::string_view word, const char* what, size_t limit, size_t data_size) {
  size_t count = 0;
  const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), count);
  if (word.empty() || ec != std::errc() || end != word.data() + word.size())
    fail(std::string("cannot parse OFF: the header's ") + what + " count is " + in_quotes(word));
  if (count > limit)
    fail("the OFF header declares " + std::string(word) + " " + what + "; meshes are limited to " +
         std::to_string(limit));
  // Each vertex and face takes at least two bytes ("0\n").
  if (count > data_size / 2)
    fail("the OFF header declares " + std::string(word) + " " + what + ", more than the file's " +
         std::to_string(data_size) + " bytes can hold");
  return count;
}

}  // namespace

// Binary STL is an 80-byte header, a 32-bit triangle count and 50 bytes per triangle; a file of
// exactly that size is binary even when its header starts with "solid" (many exporters write
// it). Anything else must be ASCII: "solid" first, text throughout.
void check_stl(const std::string& data) {
  if (data.size() >= 84) {
    uint32_t triangles = 0;
    std::memcpy(&triangles, data.data() + 80, 4);  // little-endian, as the format says
    if (data.size() == 84 + uint64_t(triangles) * 50) {
      if (triangles > kMaxMeshTriangles)
        fail("the STL file holds " + std::to_string(triangles) + " triangles; meshes are limited to " +
             std::to_string(kMaxMeshTriangles));
      return;
    }
  }
  const size_t first = data.find_first_not_of(" \t\r\n");
  if (first == std::string::npos || data.compare(first, 5, "solid") != 0) {
    if (data.size() >= 84) {
      uint32_t triangles = 0;
      std::memcpy(&triangles, data.data() + 80, 4);
      fail("cannot parse STL: a binary STL of " + std::to_string(triangles) + " triangles has " +
           std::to_string(84 + uint64_t(triangles) * 50) + " bytes, this file " + std::to_string(data.size()) +
           " (truncated?), and it is not ASCII STL (\"solid\" first)");
    }
    fail("cannot parse STL: neither binary (84 + 50 bytes per triangle) nor ASCII (\"solid\" first)");
  }
  check_text(data, "STL");
}

// OFF: "OFF" (or COFF, NOFF, CNOFF), then the vertex, face and edge counts, bounded here by the
// mesh limits and by the file's size (assimp reserves them before reading).
void check_off(const std::string& data) {
  check_text(data, "OFF");
  const std::string_view text(data);
  size_t pos = 0;
  std::string_view keyword = next_word(text, pos);
  // The counts may follow the keyword on its line ("OFF 8 6 0").
  if (keyword != "OFF" && keyword != "COFF" && keyword != "NOFF" && keyword != "CNOFF")
    fail("cannot parse OFF: expected \"OFF\" first, found " + in_quotes(keyword.substr(0, 24)));
  const size_t vertices = off_count(next_word(text, pos), "vertex", kMaxMeshVertices, data.size());
  const size_t faces = off_count(next_word(text, pos), "face", kMaxMeshTriangles, data.size());
  if (vertices + faces > data.size() / 2)
    fail("the OFF header declares " + std::to_string(vertices) + " vertices and " + std::to_string(faces) +
         " faces, more than the file's " + std::to_string(data.size()) + " bytes can hold");
}

}  // namespace caligo::mesh_detail
