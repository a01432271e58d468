#include "scene/camera.h"

#include <gtest/gtest.h>

#include <cmath>

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

}  // namespace
}  // namespace caligo
