#include "realtime/view.h"

#include <cmath>

#include "core/error.h"
#include "scene/camera.h"

namespace caligo {
namespace {

void orthonormal(View& v, Vec3 forward, Vec3 up_hint) {
  v.forward = normalize(forward);
  v.right = normalize(cross(v.forward, up_hint));
  v.up = cross(v.right, v.forward);
}

}  // namespace

View View::from_camera(const Camera& camera, Vec2i resolution) {
  if (!camera.is_pinhole())
    throw InputError("the real-time pipeline renders only pinhole perspective cameras (no \"projection\": "
                     "\"orthographic\", no \"aperture_radius\" or \"fstop\"); use `caligo render`");
  View v;
  v.projection = Projection::perspective;
  v.eye = camera.position();
  orthonormal(v, camera.forward(), camera.up_hint());
  if (camera.left_handed()) v.right = -v.right;  // the mirrored image of a left-handed camera
  v.resolution = resolution;
  v.tan_half_fov_y = camera.tan_half_fov();
  v.aspect = float(resolution.x) / float(resolution.y);
  return v;
}

View View::perspective_view(Vec3 eye, Vec3 forward, Vec3 up_hint, float fov_y, Vec2i resolution) {
  View v;
  v.projection = Projection::perspective;
  v.eye = eye;
  orthonormal(v, forward, up_hint);
  v.resolution = resolution;
  v.tan_half_fov_y = std::tan(0.5f * fov_y);
  v.aspect = float(resolution.x) / float(resolution.y);
  return v;
}

View View::orthographic_view(Vec3 eye, Vec3 forward, Vec3 up_hint, float half_width, float half_height,
                             Vec2i resolution) {
  View v;
  v.projection = Projection::orthographic;
  v.eye = eye;
  orthonormal(v, forward, up_hint);
  v.resolution = resolution;
  v.half_width = half_width;
  v.half_height = half_height;
  v.aspect = half_width / half_height;
  return v;
}

Vec3 View::project(Vec3 world) const {
  const Vec3 d = world - eye;
  const float z = dot(d, forward);
  float ndc_x, ndc_y;
  if (projection == Projection::perspective) {
    const float inv = 1.0f / (z * tan_half_fov_y);
    ndc_x = dot(d, right) * inv / aspect;
    ndc_y = dot(d, up) * inv;
  } else {
    ndc_x = dot(d, right) / half_width;
    ndc_y = dot(d, up) / half_height;
  }
  return {(ndc_x + 1.0f) * 0.5f * float(resolution.x), (1.0f - ndc_y) * 0.5f * float(resolution.y), z};
}

Ray View::ray(Vec2 film) const {
  const float ndc_x = 2.0f * film.x / float(resolution.x) - 1.0f;
  const float ndc_y = 1.0f - 2.0f * film.y / float(resolution.y);
  if (projection == Projection::perspective) {
    const Vec3 d = forward + right * (ndc_x * tan_half_fov_y * aspect) + up * (ndc_y * tan_half_fov_y);
    return {eye, normalize(d), 0.0f, kInfinity};
  }
  return {eye + right * (ndc_x * half_width) + up * (ndc_y * half_height), forward, 0.0f, kInfinity};
}

Vec3 View::unproject(Vec2 film, float depth) const {
  const Ray r = ray(film);
  return r.origin + r.direction * (depth / depth_per_t(r.direction));
}

Mat4 View::view_matrix() const {
  // Rows: right, up, -forward (eye space looks down -z), then the translation.
  Mat4 m = Mat4::identity();
  const Vec3 rows[3] = {right, up, -forward};
  for (int r = 0; r < 3; ++r) {
    m.m[r][0] = rows[r].x;
    m.m[r][1] = rows[r].y;
    m.m[r][2] = rows[r].z;
    m.m[r][3] = -dot(rows[r], eye);
  }
  return m;
}

Mat4 View::projection_matrix(float near, float far) const {
  Mat4 m{};
  if (projection == Projection::perspective) {
    m.m[0][0] = 1.0f / (tan_half_fov_y * aspect);
    m.m[1][1] = 1.0f / tan_half_fov_y;
    m.m[2][2] = -(far + near) / (far - near);
    m.m[2][3] = -2.0f * far * near / (far - near);
    m.m[3][2] = -1.0f;
  } else {
    m.m[0][0] = 1.0f / half_width;
    m.m[1][1] = 1.0f / half_height;
    m.m[2][2] = -2.0f / (far - near);
    m.m[2][3] = -(far + near) / (far - near);
    m.m[3][3] = 1.0f;
  }
  return m;
}

}  // namespace caligo
