// pbrt-v4 scene files (`caligo render scene.pbrt`): the subset of pbrt-v4's format Caligo can
// honour, turned into Caligo's scene JSON and parsed by the same parser as a .json file, so a
// pbrt scene and its JSON render to the same bits. Transforms, attributes, Include/Import,
// perspective and orthographic cameras, Film, Sampler, Integrator, PixelFilter; shapes sphere,
// disk, trianglemesh, bilinearmesh, plymesh; materials diffuse, dielectric, interface (and
// approximations with a warning); lights point, spot, distant, infinite (constant), diffuse
// area lights; media homogeneous, uniformgrid and nanovdb with MediumInterface and the camera's
// medium. Everything else is a located warning ("file:line: ...") or, where the scene cannot be
// rendered faithfully, a located InputError (docs/scene-format.md, "pbrt-v4 scenes").
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "scene/scene_desc.h"

namespace caligo {

struct PbrtConversion {
  std::string json;                   // Caligo's scene format
  std::vector<std::string> warnings;  // located
  // JSON pointer -> the pbrt directive ("file:line") it came from.
  std::vector<std::pair<std::string, std::string>> origins;
};

bool is_pbrt_path(const std::string& path);  // ends in .pbrt (any case)

PbrtConversion convert_pbrt_file(const std::string& path);
PbrtConversion convert_pbrt_text(const std::string& text, const std::string& label, const std::string& base_dir);

// The conversion parsed: errors the scene parser finds are reported at the pbrt directive.
SceneDesc parse_pbrt(const PbrtConversion& conversion, const std::string& label, const std::string& base_dir);
SceneDesc parse_pbrt_file(const std::string& path);

}  // namespace caligo
