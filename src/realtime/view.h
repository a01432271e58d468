// A pinhole or orthographic view: the camera of a frame, or a light looking at the scene
// (a shadow-map face). Pixel (x, y) has (0, 0) at the top-left corner and y growing
// downwards, exactly as in scene/camera.h, so the real-time buffers line up with the path
// tracer's pixels. Depth is LINEAR: the distance along `forward` (perspective) or from the
// near plane through `eye` along `forward` (orthographic).
#pragma once

#include "core/ray.h"
#include "core/transform.h"
#include "core/vec.h"

namespace caligo {

class Camera;

enum class Projection { perspective, orthographic };

struct View {
  Projection projection = Projection::perspective;
  Vec3 eye;                  // centre of projection, or centre of the orthographic window
  Vec3 forward, right, up;   // orthonormal; image x grows along right, image y along -up
  Vec2i resolution{1, 1};
  float tan_half_fov_y = 1.0f;  // perspective
  float aspect = 1.0f;          // width / height (perspective)
  float half_width = 1.0f, half_height = 1.0f;  // orthographic window, metres

  // The camera's view at another resolution (pixel centres scale with it).
  static View from_camera(const Camera& camera, Vec2i resolution);
  static View perspective_view(Vec3 eye, Vec3 forward, Vec3 up_hint, float fov_y_radians, Vec2i resolution);
  static View orthographic_view(Vec3 eye, Vec3 forward, Vec3 up_hint, float half_width, float half_height,
                                Vec2i resolution);

  // World point -> (pixel x, pixel y, linear depth). Perspective points behind the eye get
  // depth <= 0 (callers reject them).
  Vec3 project(Vec3 world) const;
  // The ray through film position (pixels): unit direction; orthographic rays start on the
  // window through eye. t along the ray relates to linear depth by depth = t * depth_per_t.
  Ray ray(Vec2 film) const;
  float depth_per_t(Vec3 direction) const { return dot(direction, forward); }
  // The world point seen at film position `film` at linear depth `depth`.
  Vec3 unproject(Vec2 film, float depth) const;

  // 4x4 matrices in the usual graphics convention (view: world -> eye space looking down
  // -z; projection: OpenGL-style clip space with the given near/far) for users and tools.
  Mat4 view_matrix() const;
  Mat4 projection_matrix(float near, float far) const;
};

}  // namespace caligo
