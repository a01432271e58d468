// The camera of the scene file: a perspective camera (a pinhole, or a thin lens with depth of
// field) or an orthographic one. Film coordinates are in pixels with (0, 0) at the top-left
// corner of the image and y growing downwards.
//
// Thin lens (pbrt-v4 PerspectiveCamera, Cycles' camera): a disk of radius `aperture_radius`
// centred on `position`, perpendicular to the view axis; the plane of focus lies at
// `focus_distance` along the view axis. The ray of film position f and lens sample u starts
// at the lens point (concentric disk mapping of u) and passes through the point the pinhole
// ray of f meets the plane of focus, so every point of that plane is imaged sharply where
// the pinhole images it. An f-number N gives the aperture of a 36 x 24 mm full-frame camera
// (the vertical fov spans the sensor's 24 mm height): focal length F = 12 mm / tan(fov / 2). This
// is Blender's lens only for 3:2 images: Blender fits its 36 mm sensor width to the wider side,
// so at 16:9 the same fov and f-number give Blender an aperture about 18 % smaller. Radius
// F / (2 N).
//
// Orthographic: a window of `ortho_width` x `ortho_width / aspect` metres centred on
// `position`, perpendicular to the view axis; rays start on it and run along the axis.
//
// Thread-safety: immutable after construction.
#pragma once

#include "core/ray.h"
#include "core/transform.h"
#include "scene/scene_desc.h"

namespace caligo {

// Height of the sensor an f-number refers to: 24 mm (36 x 24 mm full frame).
inline constexpr float kSensorHeightMetres = 0.024f;

class Camera {
 public:
  Camera(const CameraDesc& desc, Vec2i resolution);

  Vec2i resolution() const { return resolution_; }
  // A unit-direction ray through the film position. `lens_u` in [0, 1)^2 picks the point on
  // the aperture (sample_dim::kLens); it is ignored by pinhole and orthographic cameras, and
  // {0.5, 0.5} is the lens centre, which gives the pinhole ray.
  Ray generate_ray(Vec2 film, Vec2 lens_u = {0.5f, 0.5f}) const;
  // Distance along the viewing axis (EXR "Z") of the point at parameter t on a camera ray:
  // from the plane through position perpendicular to the axis (the lens or window plane).
  float depth(const Ray& camera_ray, float t) const { return t * dot(camera_ray.direction, forward_); }
  Vec3 position() const { return camera_to_world_.point({}); }
  // OpenEXR's camera space (its worldToCamera, RenderMan's): x to the image's right, y up, z
  // along the view, origin at position(); left-handed. A column-vector matrix, as all Mat4s.
  Mat4 world_to_view() const;
  // That space to OpenEXR's NDC after the divide by w: (0, 0) the image's top-left corner, (1, 1)
  // its bottom-right. w is the depth for a perspective camera and 1 for an orthographic one;
  // z / w (1 / depth, or the depth) keeps the matrix invertible and is discarded by readers.
  Mat4 view_to_ndc() const;
  Vec3 forward() const { return forward_; }
  Vec3 up_hint() const { return up_; }
  float tan_half_fov() const { return tan_half_fov_; }
  // Image x grows along cross(up, forward) (CameraDesc::left_handed) rather than the other way.
  bool left_handed() const { return x_sign_ > 0.0f; }

  CameraProjection projection() const { return projection_; }
  // Orthographic window in metres (zero for perspective cameras).
  float ortho_width() const { return ortho_width_; }
  float ortho_height() const { return ortho_width_ / aspect_; }
  float aperture_radius() const { return aperture_radius_; }
  float focus_distance() const { return focus_distance_; }
  // Whether generate_ray reads lens_u: draw the lens sample only then.
  bool has_aperture() const { return aperture_radius_ > 0.0f; }
  // A perspective camera without aperture: what the real-time pipeline renders.
  bool is_pinhole() const { return projection_ == CameraProjection::perspective && !has_aperture(); }

  // The lens of a 24 mm-high sensor: F = (h / 2) / tan(fov / 2), aperture radius F / (2 N).
  static float focal_length(float fov_degrees);
  static float aperture_radius_for_fstop(float fstop, float fov_degrees);

 private:
  Transform camera_to_world_;
  Vec3 forward_;
  Vec3 up_;
  Vec2i resolution_;
  float x_sign_;  // -1: image x along cross(forward, up); +1 left-handed
  float tan_half_fov_;
  float aspect_;
  CameraProjection projection_;
  float ortho_width_;
  float aperture_radius_;
  float focus_distance_;
};

}  // namespace caligo
