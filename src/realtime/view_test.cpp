#include "realtime/view.h"

#include <gtest/gtest.h>

#include "scene/camera.h"

namespace caligo {
namespace {

// The real-time camera view must put every world point on the same pixel as the path
// tracer's camera ray through that pixel.
TEST(View, MatchesThePathTracersCameraRays) {
  CameraDesc desc;
  desc.position = {1.0f, 2.0f, 3.0f};
  desc.look_at = {-0.5f, 0.3f, -1.0f};
  desc.fov_degrees = 50.0f;
  const Vec2i res{320, 200};
  const Camera camera(desc, res);
  const View view = View::from_camera(camera, res);
  for (Vec2 film : {Vec2{0.5f, 0.5f}, Vec2{160.0f, 100.0f}, Vec2{300.25f, 17.5f}, Vec2{3.0f, 190.0f}}) {
    const Ray a = camera.generate_ray(film);
    const Ray b = view.ray(film);
    EXPECT_NEAR(dot(a.direction, b.direction), 1.0f, 1e-6f);
    const Vec3 p = a.origin + a.direction * 7.0f;
    const Vec3 q = view.project(p);
    EXPECT_NEAR(q.x, film.x, 1e-3f);
    EXPECT_NEAR(q.y, film.y, 1e-3f);
    EXPECT_NEAR(q.z, camera.depth(a, 7.0f), 1e-4f);
    const Vec3 back = view.unproject(film, q.z);
    EXPECT_NEAR(distance(back, p), 0.0f, 1e-4f);
  }
}

TEST(View, OrthographicProjectsAlongForward) {
  const View v = View::orthographic_view({0, 5, 0}, {0, -1, 0}, {0, 0, -1}, 2.0f, 1.0f, {100, 50});
  const Vec3 q = v.project({1.0f, 2.0f, -0.5f});
  EXPECT_NEAR(q.z, 3.0f, 1e-6f);
  const Ray r = v.ray({q.x, q.y});
  EXPECT_NEAR(distance(r.origin + r.direction * 3.0f, Vec3(1.0f, 2.0f, -0.5f)), 0.0f, 1e-5f);
}

// The matrices agree with project(): clip-space x/w, y/w are the NDC that project() maps to pixels.
TEST(View, MatricesAgreeWithProject) {
  const View v = View::perspective_view({0, 1, 4}, {0, -0.2f, -1}, {0, 1, 0}, 1.0f, {64, 48});
  const Mat4 vp = v.projection_matrix(0.1f, 100.0f) * v.view_matrix();
  const Vec3 p{0.7f, 0.4f, -2.0f};
  float clip[4];
  for (int r = 0; r < 4; ++r) clip[r] = vp.m[r][0] * p.x + vp.m[r][1] * p.y + vp.m[r][2] * p.z + vp.m[r][3];
  const Vec3 q = v.project(p);
  EXPECT_NEAR((clip[0] / clip[3] + 1.0f) * 0.5f * 64.0f, q.x, 1e-3f);
  EXPECT_NEAR((1.0f - clip[1] / clip[3]) * 0.5f * 48.0f, q.y, 1e-3f);
  EXPECT_NEAR(clip[3], q.z, 1e-5f);
}

}  // namespace
}  // namespace caligo
