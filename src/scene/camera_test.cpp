#include "scene/camera.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace caligo {
namespace {

CameraDesc looking_down_minus_z() {
  CameraDesc desc;
  desc.position = {0, 0, 5};
  desc.look_at = {0, 0, 0};
  desc.fov_degrees = 90.0f;
  return desc;
}

TEST(Camera, CentreRayLooksAtTheTarget) {
  const Camera camera(looking_down_minus_z(), {200, 100});
  const Ray r = camera.generate_ray({100, 50});
  EXPECT_NEAR(r.direction.z, -1.0f, 1e-6f);
  EXPECT_EQ(r.origin, Vec3(0, 0, 5));
}

TEST(Camera, ImageAxesAreRightAndDown) {
  const Camera camera(looking_down_minus_z(), {100, 100});
  // Seen from +Z looking at the origin with +Y up, the viewer's right is +X.
  EXPECT_GT(camera.generate_ray({99, 50}).direction.x, 0.0f);
  EXPECT_LT(camera.generate_ray({50, 99}).direction.y, 0.0f);
}

TEST(Camera, VerticalFieldOfViewAndAspect) {
  const Camera camera(looking_down_minus_z(), {200, 100});
  // fov 90 degrees: the top edge of the film is 45 degrees above the axis.
  const Ray top = camera.generate_ray({100, 0});
  EXPECT_NEAR(std::atan2(top.direction.y, -top.direction.z), 0.25f * kPi, 1e-5f);
  // Aspect 2: the right edge is at atan(2).
  const Ray right = camera.generate_ray({200, 50});
  EXPECT_NEAR(std::atan2(right.direction.x, -right.direction.z), std::atan(2.0f), 1e-5f);
}

TEST(Camera, DepthIsMeasuredAlongTheViewAxis) {
  const Camera camera(looking_down_minus_z(), {100, 100});
  const Ray corner = camera.generate_ray({0, 0});
  // The plane z = 0 lies at depth 5 whichever pixel sees it.
  const float t = 5.0f / -corner.direction.z;
  EXPECT_NEAR(camera.depth(corner, t), 5.0f, 1e-5f);
}

// ---- orthographic ----

// Looking straight down from y = 5 with image-up towards -z: image x is +x, image y is +z.
CameraDesc ortho_looking_down() {
  CameraDesc desc;
  desc.position = {1, 5, 2};
  desc.look_at = {1, 0, 2};
  desc.up = {0, 0, -1};
  desc.projection = CameraProjection::orthographic;
  desc.ortho_width = 4.0f;
  return desc;
}

TEST(Camera, OrthographicRaysAreParallelAndSpanTheWindow) {
  const Camera camera(ortho_looking_down(), {200, 100});
  EXPECT_FLOAT_EQ(camera.ortho_height(), 2.0f);  // 4 m wide at aspect 2
  for (Vec2 film : {Vec2{0, 0}, Vec2{200, 100}, Vec2{37.5f, 80.25f}, Vec2{100, 50}}) {
    const Ray r = camera.generate_ray(film, {0.9f, 0.1f});
    EXPECT_EQ(r.direction, Vec3(0, -1, 0));
    // Origins on the window through position: x = 1 - 2 + 4 film.x / 200, z = 2 - 1 + 2 film.y / 100.
    EXPECT_NEAR(r.origin.x, -1.0f + 4.0f * film.x / 200.0f, 1e-5f);
    EXPECT_NEAR(r.origin.y, 5.0f, 1e-5f);
    EXPECT_NEAR(r.origin.z, 1.0f + 2.0f * film.y / 100.0f, 1e-5f);
  }
  // Depth is the distance from the window plane.
  const Ray r = camera.generate_ray({10, 10});
  EXPECT_NEAR(camera.depth(r, 3.5f), 3.5f, 1e-6f);
  EXPECT_FALSE(camera.is_pinhole());
  EXPECT_FALSE(camera.has_aperture());
}

// OpenEXR's worldToNDC (view_to_ndc * world_to_view) takes a point seen through film position f
// to f / resolution, for both handednesses and both projections; worldToCamera has z along the
// view and x to the image's right.
Vec2 ndc_of(const Camera& camera, Vec3 p) {
  const Mat4 m = camera.view_to_ndc() * camera.world_to_view();
  float h[4];
  for (int r = 0; r < 4; ++r) h[r] = m.m[size_t(r)][0] * p.x + m.m[size_t(r)][1] * p.y + m.m[size_t(r)][2] * p.z + m.m[size_t(r)][3];
  return {h[0] / h[3], h[1] / h[3]};
}

TEST(Camera, ExrMatricesProjectWhereTheRaysGo) {
  CameraDesc tilted;
  tilted.position = {0.5f, 1.5f, 3.0f};
  tilted.look_at = {-0.3f, 0.2f, -1.0f};
  tilted.fov_degrees = 50.0f;
  CameraDesc mirrored = tilted;
  mirrored.left_handed = true;
  for (const CameraDesc& desc : {tilted, mirrored, ortho_looking_down()}) {
    const Camera camera(desc, {160, 90});
    for (Vec2 film : {Vec2{0, 0}, Vec2{160, 90}, Vec2{12.5f, 70.25f}, Vec2{80, 45}}) {
      const Ray r = camera.generate_ray(film);
      const Vec2 ndc = ndc_of(camera, r.origin + r.direction * 2.7f);
      EXPECT_NEAR(ndc.x, film.x / 160.0f, 1e-5f);
      EXPECT_NEAR(ndc.y, film.y / 90.0f, 1e-5f);
    }
    const Mat4 view = camera.world_to_view();
    const auto& v = view.m;
    const Vec3 ahead = camera.position() + camera.forward() * 2.0f;
    EXPECT_NEAR(v[2][0] * ahead.x + v[2][1] * ahead.y + v[2][2] * ahead.z + v[2][3], 2.0f, 1e-5f);
    const Ray right = camera.generate_ray({150, 45});
    const Vec3 q = right.origin + right.direction;
    EXPECT_GT(v[0][0] * q.x + v[0][1] * q.y + v[0][2] * q.z + v[0][3], 0.0f);
  }
}

// ---- thin lens ----

CameraDesc thin_lens() {
  CameraDesc desc;
  desc.position = {0.3f, 1.2f, 4.0f};
  desc.look_at = {-0.2f, 0.9f, 0.5f};
  desc.fov_degrees = 35.0f;
  desc.aperture_radius = 0.05f;
  desc.focus_distance = 2.5f;
  return desc;
}

// Point where a ray meets the plane at `depth` along the camera's axis from its position.
Vec3 at_depth(const Camera& camera, const Ray& r, float depth) {
  const float t = (depth - dot(r.origin - camera.position(), camera.forward())) / dot(r.direction, camera.forward());
  return r.origin + r.direction * t;
}

std::vector<Vec2> lens_samples() {
  std::vector<Vec2> u;
  for (int j = 0; j < 7; ++j)
    for (int i = 0; i < 7; ++i) u.push_back({(float(i) + 0.5f) / 7.0f, (float(j) + 0.3f) / 7.0f});
  u.push_back({0.0f, 0.0f});
  u.push_back({0.999f, 0.5f});
  return u;
}

// Every ray of one film position passes through the point where the pinhole ray meets the
// plane of focus: the distance from that point to each ray's line is zero.
TEST(Camera, ThinLensRaysMeetAtTheFocusPoint) {
  const CameraDesc desc = thin_lens();
  const Camera camera(desc, {160, 90});
  CameraDesc pinhole_desc = desc;
  pinhole_desc.aperture_radius = 0.0f;
  const Camera pinhole(pinhole_desc, {160, 90});
  for (Vec2 film : {Vec2{80, 45}, Vec2{0.5f, 0.5f}, Vec2{150.25f, 12.0f}, Vec2{3, 88}}) {
    const Ray p = pinhole.generate_ray(film);
    const Vec3 focus = p.origin + p.direction * (desc.focus_distance / dot(p.direction, pinhole.forward()));
    for (Vec2 u : lens_samples()) {
      const Ray r = camera.generate_ray(film, u);
      EXPECT_NEAR(length(r.direction), 1.0f, 1e-6f);
      const Vec3 to_focus = focus - r.origin;
      const Vec3 off_line = to_focus - r.direction * dot(to_focus, r.direction);
      EXPECT_LT(length(off_line), 1e-5f) << film.x << "," << film.y << " u " << u.x << "," << u.y;
      // The origin is on the lens: in the plane through position, within the aperture.
      EXPECT_NEAR(dot(r.origin - camera.position(), camera.forward()), 0.0f, 1e-6f);
      EXPECT_LE(length(r.origin - camera.position()), desc.aperture_radius * (1.0f + 1e-5f));
    }
    // The lens centre gives the pinhole ray.
    const Ray c = camera.generate_ray(film, {0.5f, 0.5f});
    EXPECT_EQ(c.origin, p.origin);
    EXPECT_NEAR(dot(c.direction, p.direction), 1.0f, 1e-6f);
  }
}

// Geometry of the image: a plane at the focus distance is imaged exactly where the pinhole
// images it; a plane at depth D spreads a film point over a disk of radius R |1 - D / F|
// (the circle of confusion), reached by lens samples on the rim. Depth stays the axial distance.
TEST(Camera, InFocusPlaneLandsWhereThePinholeSeesIt) {
  const CameraDesc desc = thin_lens();
  const Camera camera(desc, {160, 90});
  const Camera pinhole([&] {
    CameraDesc d = desc;
    d.aperture_radius = 0.0f;
    return d;
  }(), {160, 90});
  const float f = desc.focus_distance;
  for (Vec2 film : {Vec2{80, 45}, Vec2{17.5f, 70.0f}}) {
    const Ray p = pinhole.generate_ray(film);
    for (float depth : {f, 1.0f, 6.0f}) {
      const Vec3 sharp = at_depth(pinhole, p, depth);
      float spread = 0.0f;
      for (Vec2 u : lens_samples()) {
        const Ray r = camera.generate_ray(film, u);
        const Vec3 hit = at_depth(camera, r, depth);
        spread = std::max(spread, distance(hit, sharp));
        const float t = dot(hit - r.origin, r.direction);
        EXPECT_NEAR(camera.depth(r, t), depth, 1e-4f);
      }
      const float confusion = desc.aperture_radius * std::abs(1.0f - depth / f);
      if (depth == f)
        EXPECT_LT(spread, 1e-5f);
      else
        EXPECT_NEAR(spread, confusion, 2e-3f * confusion) << "depth " << depth;
    }
  }
}

TEST(Camera, FocusDistanceDefaultsToTheTarget) {
  CameraDesc desc = thin_lens();
  desc.focus_distance = 0.0f;
  const Camera camera(desc, {64, 64});
  EXPECT_FLOAT_EQ(camera.focus_distance(), length(desc.look_at - desc.position));
}

// A 50 mm lens on a 24 mm-high sensor has a vertical field of view of 2 atan(12 / 50); at
// f/2 its aperture is 25 mm across.
TEST(Camera, FNumberGivesTheFullFrameAperture) {
  const float fov = 2.0f * std::atan(12.0f / 50.0f) * 180.0f / kPi;
  EXPECT_NEAR(Camera::focal_length(fov), 0.050f, 1e-6f);
  EXPECT_NEAR(Camera::aperture_radius_for_fstop(2.0f, fov), 0.0125f, 1e-6f);
  CameraDesc desc = thin_lens();
  desc.aperture_radius = 0.0f;
  desc.fstop = 2.0f;
  desc.fov_degrees = fov;
  const Camera camera(desc, {64, 64});
  EXPECT_NEAR(camera.aperture_radius(), 0.0125f, 1e-6f);
  EXPECT_TRUE(camera.has_aperture());
  EXPECT_FALSE(camera.is_pinhole());
}

}  // namespace
}  // namespace caligo
