// Scenes, media and lights built in code for the scene-buffer, shadow-map, surface-shading,
// accumulation and froxel tests (test code only).
#pragma once

#include <cmath>
#include <string>
#include <vector>

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

// A box of homogeneous medium.
inline VolumePrimitive fog_box(Vec3 lo, Vec3 hi, RGB sigma_a, RGB sigma_s, PhaseFunction phase = IsotropicPhase{}) {
  VolumePrimitive p;
  p.shape = BoxVolumeShape{Transform(), lo, hi};
  p.shader.sigma_a = sigma_a;
  p.shader.sigma_s = sigma_s;
  p.shader.phase = phase;
  return p;
}

// One light of each type the passes march: a point, a spot, a box and a directional light,
// placed for the accumulation tests' comparison scene (test code only).
inline std::vector<Light> delta_lights() {
  PointLight point{{0.5f, 1.0f, -3.0f}, RGB(5.0f, 4.0f, 3.0f), 4.0f};
  SpotLight spot;
  spot.position = {-1.0f, 2.5f, -4.0f};
  spot.direction = normalize(Vec3(0.3f, -1.0f, -0.2f));
  spot.cos_inner = std::cos(radians(18.0f));
  spot.cos_outer = std::cos(radians(30.0f));
  spot.intensity = RGB(20.0f);
  spot.range = 8.0f;
  BoxLight box;
  box.position = {1.0f, 3.0f, -5.0f};
  box.direction = {0.0f, -1.0f, 0.0f};
  box.up = {0.0f, 0.0f, 1.0f};
  box.half_width = 0.7f;
  box.half_height = 1.5f;
  box.range = 4.0f;
  box.irradiance = RGB(2.0f, 3.0f, 4.0f);
  DirectionalLight sun{normalize(Vec3(0.4f, -1.0f, -0.3f)), RGB(1.5f)};
  return {point, spot, box, sun};
}

}  // namespace caligo::test_scenes
