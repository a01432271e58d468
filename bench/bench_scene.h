// The scenes benchmarks run on, built once per process.
#pragma once

#include <memory>
#include <string>

#include "scene/builtins.h"
#include "scene/scene.h"
#include "scene/scene_parser.h"

namespace caligo::bench {

inline const Scene& builtin_scene(const std::string& name) {
  static std::unique_ptr<Scene> scene;
  static std::string loaded;
  if (!scene || loaded != name) {
    const BuiltinScene* b = find_builtin(name);
    scene = Scene::build(parse_scene_text(b->json, "builtin:" + name, "."));
    loaded = name;
  }
  return *scene;
}

}  // namespace caligo::bench
