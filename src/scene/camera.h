// The pinhole perspective camera of the scene file. Film coordinates are in pixels with
// (0, 0) at the top-left corner of the image and y growing downwards.
#pragma once

#include "core/ray.h"
#include "core/transform.h"
#include "scene/scene_desc.h"

namespace caligo {

class Camera {
 public:
  Camera(const CameraDesc& desc, Vec2i resolution);

  Vec2i resolution() const { return resolution_; }
  // A unit-direction ray through the film position.
  Ray generate_ray(Vec2 film) const;
  // Distance along the viewing axis (EXR "Z") of the point at parameter t on a camera ray.
  float depth(const Ray& camera_ray, float t) const { return t * dot(camera_ray.direction, forward_); }
  Vec3 position() const { return camera_to_world_.point({}); }
  Vec3 forward() const { return forward_; }
  Vec3 up_hint() const { return up_; }
  float tan_half_fov() const { return tan_half_fov_; }

 private:
  Transform camera_to_world_;
  Vec3 forward_;
  Vec3 up_;
  Vec2i resolution_;
  float tan_half_fov_;
  float aspect_;
};

}  // namespace caligo
