#include "scene/camera.h"

#include <cmath>

namespace caligo {

Camera::Camera(const CameraDesc& desc, Vec2i resolution)
    : camera_to_world_(Transform::look_at(desc.position, desc.look_at, desc.up)),
      forward_(normalize(desc.look_at - desc.position)),
      up_(desc.up),
      resolution_(resolution),
      tan_half_fov_(std::tan(0.5f * radians(desc.fov_degrees))),
      aspect_(float(resolution.x) / float(resolution.y)) {}

// Transform::look_at maps local +X to cross(up, forward), which in a right-handed frame is
// the viewer's left; image x grows to the viewer's right, hence the minus sign.
Ray Camera::generate_ray(Vec2 film) const {
  const float ndc_x = 2.0f * film.x / float(resolution_.x) - 1.0f;
  const float ndc_y = 1.0f - 2.0f * film.y / float(resolution_.y);
  const Vec3 local(-ndc_x * tan_half_fov_ * aspect_, ndc_y * tan_half_fov_, 1.0f);
  return {position(), normalize(camera_to_world_.vector(local)), 0.0f, kInfinity};
}

}  // namespace caligo
