// Scenes built in code for the scene-buffer, shadow-map and surface-shading tests (test
// code only).
#pragma once

#include <cmath>
#include <string>

#include "scene/scene.h"
#include "scene/scene_desc.h"

namespace caligo::test_scenes {

inline int add_diffuse(SceneDesc& desc, float albedo) {
  desc.materials.push_back(
      {"diffuse" + std::to_string(desc.materials.size()), DiffuseBsdf{RGB(albedo)}, {}, false});
  return int(desc.materials.size()) - 1;
}

// A floor, a box, a sphere and a tilted two-sided quad, seen from above and in front.
inline SceneDesc box_sphere_quad() {
  SceneDesc desc;
  desc.file = "test";
  desc.camera.position = {0.5f, 2.5f, 6.0f};
  desc.camera.look_at = {0.0f, 0.6f, 0.0f};
  desc.camera.fov_degrees = 50.0f;
  const int m = add_diffuse(desc, 0.5f);
  desc.shapes.push_back({RectangleShape{{-4, 0, 4}, {8, 0, 0}, {0, 0, -8}}, {}, m});
  desc.shapes.push_back({BoxShape{{-2.2f, 0, -1}, {-0.6f, 1.2f, 0.5f}}, {}, m});
  desc.shapes.push_back({SphereShape{{1.2f, 0.9f, 0.2f}, 0.8f}, {}, m});
  desc.shapes.push_back({RectangleShape{{-0.5f, 0, 0}, {1.0f, 0, 0}, {0, 1.0f, 0}},
                         Transform::translate({0.2f, 1.0f, 1.5f}) * Transform::rotate(0.6f, {1, 1, 0}), m});
  return desc;
}

}  // namespace caligo::test_scenes
