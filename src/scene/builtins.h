// Scenes compiled into the binary, usable by name (`caligo render furnace`). Each is JSON
// text in the ordinary scene format, parsed by the same parser as files, so a builtin is
// also an example of the format. Some have closed-form answers the tests rely on; their
// descriptions say what the answer is.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "scene/scene_desc.h"

namespace caligo {

struct BuiltinScene {
  std::string name;         // e.g. "furnace"
  std::string description;  // one line, for `caligo render --list-builtins`
  std::string json;         // the scene, format v1
};

// Every builtin, in a fixed order (the default scene first).
std::vector<BuiltinScene> builtin_scenes();

// The builtin called `name`, or nullptr. The pointer stays valid for the whole program.
const BuiltinScene* find_builtin(std::string_view name);

// Parses a builtin; errors (there should be none) name it "builtin:<name>".
SceneDesc parse_builtin(const BuiltinScene& scene);

}  // namespace caligo
