// The JSON scene format, version 1 (docs/scene-format.md) -> SceneDesc.
//
// Everything the format can get wrong is checked here, so later stages can trust a
// SceneDesc: every failure is an InputError whose what() reads
//   "<file>: <JSON pointer>: <what was expected>, got <what was found>"
// (syntax errors give "line L, column C" in place of the pointer). Unit conversions
// happen here too: degrees become radians or cosines, light powers (W) become
// intensities (W/sr) or radiances (W m^-2 sr^-1), directions are normalised and a
// light's "color" is multiplied into its quantity.
#pragma once

#include <optional>
#include <string>

#include "scene/scene_desc.h"

namespace caligo {

// Reads and parses a scene file. Relative mesh paths are resolved against the directory
// of `path`. An unreadable file is an InputError naming it.
// `frame`: the frame of a sequence render, which "{frame}" in the scene's file names becomes.
SceneDesc parse_scene_file(const std::string& path, std::optional<int> frame = std::nullopt);

// Parses scene text. `file_label` names the input in errors and becomes SceneDesc::file;
// relative mesh paths are resolved against `base_dir` (left as written when it is empty).
SceneDesc parse_scene_text(const std::string& json_text, const std::string& file_label,
                           const std::string& base_dir, std::optional<int> frame = std::nullopt);

}  // namespace caligo
