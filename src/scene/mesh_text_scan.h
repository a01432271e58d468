// Checks on the text of glTF and COLLADA files, run before the parsing libraries see it, for
// inputs that crash those libraries rather than making them report an error. Each returns the
// problem as a message (with a line number where there is one), or an empty string.
//
// - Nesting: tinygltf (nlohmann::json, then its own Value conversion) and assimp's COLLADA
//   reader recurse once per level; a few thousand levels overflow the stack (SIGSEGV). Levels
//   are counted here without recursion, against kMaxGltfJsonDepth and kMaxColladaDepth.
// - COLLADA accessors: assimp 5.2 reads an <accessor>'s values from its source array without
//   checking the array is long enough (a <float_array> without "count" holds none: a null
//   read, found by fuzz/mesh_fuzz.cpp). Every accessor must fit in the array it names.
//
// The scans read the markup only: a malformed file they pass is left to the library to refuse.
#pragma once

#include <string>
#include <string_view>

namespace caligo {

// A .gltf's JSON, or a GLB container's JSON chunk (the container recognised by its magic).
std::string gltf_nesting_problem(std::string_view file);

// A COLLADA file: scanned as assimp 5.2 parses it (UTF-8 up to the first NUL byte, whatever
// a byte-order mark says) and, when it looks like UTF-16 or UTF-32, decoded as such too.
std::string collada_nesting_problem(std::string_view file);
std::string collada_accessor_problem(std::string_view file);

}  // namespace caligo
