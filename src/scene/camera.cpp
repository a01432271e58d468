#include "scene/camera.h"

#include <cmath>

#include "core/sampling.h"

namespace caligo {
namespace {

float resolve_aperture(const CameraDesc& desc) {
  if (desc.projection != CameraProjection::perspective) return 0.0f;
  if (desc.fstop > 0.0f) return Camera::aperture_radius_for_fstop(desc.fstop, desc.fov_degrees);
  return desc.aperture_radius;
}

}  // namespace

float Camera::focal_length(float fov_degrees) {
  return 0.5f * kSensorHeightMetres / std::tan(0.5f * radians(fov_degrees));
}

float Camera::aperture_radius_for_fstop(float fstop, float fov_degrees) {
  return focal_length(fov_degrees) / (2.0f * fstop);
}

Camera::Camera(const CameraDesc& desc, Vec2i resolution)
    : camera_to_world_(Transform::look_at(desc.position, desc.look_at, desc.up)),
      forward_(normalize(desc.look_at - desc.position)),
      up_(desc.up),
      resolution_(resolution),
      x_sign_(desc.left_handed ? 1.0f : -1.0f),
      tan_half_fov_(std::tan(0.5f * radians(desc.fov_degrees))),
      aspect_(float(resolution.x) / float(resolution.y)),
      projection_(desc.projection),
      ortho_width_(desc.projection == CameraProjection::orthographic ? desc.ortho_width : 0.0f),
      aperture_radius_(resolve_aperture(desc)),
      focus_distance_(desc.focus_distance > 0.0f ? desc.focus_distance : length(desc.look_at - desc.position)) {}

// Transform::look_at maps local +X to cross(up, forward), which in a right-handed frame is
// the viewer's left; image x grows to the viewer's right, hence x_sign_ = -1 (+1 for a
// left-handed camera, whose image is mirrored).
Ray Camera::generate_ray(Vec2 film, Vec2 lens_u) const {
  const float ndc_x = 2.0f * film.x / float(resolution_.x) - 1.0f;
  const float ndc_y = 1.0f - 2.0f * film.y / float(resolution_.y);
  if (projection_ == CameraProjection::orthographic) {
    const Vec3 local(x_sign_ * ndc_x * 0.5f * ortho_width_, ndc_y * 0.5f * ortho_height(), 0.0f);
    return {camera_to_world_.point(local), forward_, 0.0f, kInfinity};
  }
  // Local pinhole direction with unit z: it meets the plane of focus at focus_distance * d.
  const Vec3 d(x_sign_ * ndc_x * tan_half_fov_ * aspect_, ndc_y * tan_half_fov_, 1.0f);
  if (!has_aperture()) return {position(), normalize(camera_to_world_.vector(d)), 0.0f, kInfinity};
  const Vec2 disk = sample_uniform_disk_concentric(lens_u);
  const Vec3 lens(disk.x * aperture_radius_, disk.y * aperture_radius_, 0.0f);
  const Vec3 focus = d * focus_distance_;
  return {camera_to_world_.point(lens), normalize(camera_to_world_.vector(focus - lens)), 0.0f, kInfinity};
}

Mat4 Camera::world_to_view() const {
  Mat4 flip = Mat4::identity();
  flip.m[0][0] = x_sign_;  // camera-local x is cross(up, forward); the image's right is x_sign_ times it
  return flip * camera_to_world_.inverse_matrix();
}

Mat4 Camera::view_to_ndc() const {
  Mat4 p{};
  if (projection_ == CameraProjection::orthographic) {
    p.m[0] = {1.0f / ortho_width_, 0.0f, 0.0f, 0.5f};
    p.m[1] = {0.0f, -1.0f / ortho_height(), 0.0f, 0.5f};
    p.m[2] = {0.0f, 0.0f, 1.0f, 0.0f};
    p.m[3] = {0.0f, 0.0f, 0.0f, 1.0f};
    return p;
  }
  // x / z spans [-tan * aspect, tan * aspect] over the width, y / z [-tan, tan] over the height.
  p.m[0] = {0.5f / (tan_half_fov_ * aspect_), 0.0f, 0.5f, 0.0f};
  p.m[1] = {0.0f, -0.5f / tan_half_fov_, 0.5f, 0.0f};
  p.m[2] = {0.0f, 0.0f, 0.0f, 1.0f};
  p.m[3] = {0.0f, 0.0f, 1.0f, 0.0f};
  return p;
}

}  // namespace caligo
