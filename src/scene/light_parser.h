// Reading lights from scene JSON (docs/scene-format.md, "lights"): the light itself, with
// powers converted to intensities/irradiances, gobo images and IES profiles loaded (paths
// relative to the scene file), and the per-light real-time options and animation.
#pragma once

#include <map>
#include <memory>
#include <string>

#include "lights/light.h"
#include "scene/json_reader.h"
#include "scene/scene_desc.h"
#include "scene/shared_readers.h"

namespace caligo {

// Files read while parsing one scene, so lights sharing a gobo or profile share one copy.
struct LightFileCache {
  SceneFiles& files;
  std::map<std::string, std::shared_ptr<const GoboImage>> gobos;
  std::map<std::string, std::shared_ptr<const IesProfile>> profiles;
  std::map<std::string, std::shared_ptr<const EnvironmentMap>> environment_maps;
};

struct ParsedLight {
  Light light;
  LightOptions options;
};

// One element of "lights".
ParsedLight parse_light(const JsonCursor& c, LightFileCache& files);

}  // namespace caligo
