// Test-only helpers for building SceneDescs in code (the integrator tests).
#pragma once

#include "scene/scene_desc.h"

namespace caligo::testing {

// A scene with only a camera (file "test", up +Y).
inline SceneDesc camera_at(Vec3 position, Vec3 look_at, Vec2i resolution, float fov_degrees) {
  SceneDesc desc;
  desc.file = "test";
  desc.camera = {position, look_at, {0, 1, 0}, fov_degrees, resolution};
  return desc;
}

}  // namespace caligo::testing
