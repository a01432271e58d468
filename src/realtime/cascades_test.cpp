// A sun's cascaded shadow maps (realtime/directional_faces.h): thin shadows near the camera
// resolved where the one face over a large scene misses them, the SIMD lookup against the
// scalar one, and faces reused until the camera has moved a margin.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "realtime/directional_faces.h"
#include "realtime/scene_buffers.h"
#include "realtime/shadow_map.h"
#include "realtime/shadow_map_simd.h"
#include "realtime/test_scenes.h"
#include "scene/scene.h"

namespace caligo {
namespace {

// A 200 m ground and, 3 to 7 m in front of the camera, poles 5 cm thick: at 512 texels over
// the whole ground a texel is 39 cm, so their shadows fall between texel centres.
struct PoleField {
  std::unique_ptr<Scene> scene;
  RasterScene raster;
  Bounds3 bounds;
  View camera = View::perspective_view({0, 1.7f, 0}, normalize(Vec3(0, -0.35f, -1)), {0, 1, 0}, radians(60.0f),
                                       {320, 180});
  Vec3 sun = normalize(Vec3(0.6f, -1.0f, -0.25f));

  PoleField() : scene(Scene::build(desc())), raster(RasterScene::build(*scene)), bounds(scene->surfaces().bounds()) {}

  static SceneDesc desc() {
    SceneDesc d;
    d.file = "poles";
    const int m = test_scenes::add_diffuse(d, 0.5f);
    d.shapes.push_back({RectangleShape{{-100, 0, 100}, {200, 0, 0}, {0, 0, -200}}, {}, m});
    for (int i = 0; i < 9; ++i) {
      const float x = -2.0f + 0.5f * float(i), z = -3.0f - 0.5f * float(i);
      d.shapes.push_back({BoxShape{{x, 0, z}, {x + 0.05f, 3.0f, z + 0.05f}}, {}, m});
    }
    return d;
  }

  bool lit(Vec3 p) const {
    const Ray ray{p, -sun, 1e-4f, 1e3f};
    return !scene->surfaces().occluded(ray);
  }
};

// Ground points seen by the camera within 10 m.
std::vector<Vec3> ground_points(const PoleField& f) {
  std::vector<Vec3> points;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  while (points.size() < 60000) {
    const Ray r = f.camera.ray({u(rng) * 320.0f, u(rng) * 180.0f});
    if (r.direction.y >= 0.0f) continue;
    const float t = -r.origin.y / r.direction.y;
    const Vec3 p = r.at(t);
    if (f.camera.depth_per_t(r.direction) * t < 10.0f) points.push_back(Vec3(p.x, 1e-3f, p.z));
  }
  return points;
}

struct Recall {
  int shadowed = 0, found = 0, false_shadow = 0;
};

Recall recall(const PoleField& f, const ShadowMap& map, const std::vector<Vec3>& points) {
  Recall r;
  for (const Vec3& p : points) {
    const bool lit = f.lit(p), map_lit = map.surface_visibility(p) > 0.5f;
    r.shadowed += !lit;
    r.found += !lit && !map_lit;
    r.false_shadow += lit && !map_lit;
  }
  return r;
}

TEST(Cascades, ResolveThinShadowsNearTheCamera) {
  const PoleField f;
  const std::vector<Vec3> points = ground_points(f);
  const auto whole = render_shadow_map(f.raster, DirectionalLight{f.sun, RGB(1.0f)}, 512, f.bounds);
  ASSERT_TRUE(whole);
  ShadowMap cascades;
  const CascadeFaces fit = fit_cascades(f.camera, 0.4f, 200.0f, f.sun, f.bounds, 4, 512);
  EXPECT_EQ(update_cascaded_shadow_map(f.raster, fit, f.camera, -1, cascades), 4);
  const Recall one = recall(f, *whole, points), four = recall(f, cascades, points);
  std::printf("pole shadows within 10 m: %d points; one face finds %d (%d false), cascades %d (%d false)\n",
              one.shadowed, one.found, one.false_shadow, four.found, four.false_shadow);
  // Measured: of 628 shadowed points one face finds 121 and shadows 430 lit ones; cascades
  // find 557 and shadow 71 (texels of 2 to 4 cm against a 5 cm shadow, edges within a texel).
  ASSERT_GT(one.shadowed, 300);
  EXPECT_LT(one.found, one.shadowed * 3 / 10);
  EXPECT_GT(four.found, four.shadowed * 8 / 10);
  EXPECT_LT(four.false_shadow, four.shadowed * 15 / 100);
  const int one_wrong = one.shadowed - one.found + one.false_shadow;
  const int four_wrong = four.shadowed - four.found + four.false_shadow;
  EXPECT_LT(4 * four_wrong, one_wrong);
  // Each point in the face of its camera depth, SIMD as scalar.
  using B = xsimd::batch<float>;
  int mismatch = 0;
  for (size_t i = 0; i + B::size <= points.size(); i += B::size) {
    alignas(32) float x[B::size], y[B::size], z[B::size], v[B::size];
    for (size_t k = 0; k < B::size; ++k) x[k] = points[i + k].x, y[k] = points[i + k].y, z[k] = points[i + k].z;
    surface_shadow_visibility(cascades, B::load_aligned(x), B::load_aligned(y), B::load_aligned(z)).store_aligned(v);
    for (size_t k = 0; k < B::size; ++k) mismatch += std::abs(v[k] - cascades.surface_visibility(points[i + k])) > 1e-3f;
  }
  EXPECT_LE(mismatch, int(points.size()) / 1000);
}

TEST(Cascades, SplitsRunFromNearToFar) {
  const std::vector<float> s = cascade_splits(0.5f, 100.0f, 4, 0.75f);
  ASSERT_EQ(s.size(), 4u);
  EXPECT_EQ(s.back(), 100.0f);
  for (size_t i = 1; i < s.size(); ++i) EXPECT_GT(s[i], s[i - 1]);
  // lambda 1: the logarithmic split, each range the same ratio far / near.
  const std::vector<float> log = cascade_splits(1.0f, 16.0f, 4, 1.0f);
  EXPECT_NEAR(log[0], 2.0f, 1e-5f);
  EXPECT_NEAR(log[2], 8.0f, 1e-4f);
}

// A camera walking 3 m in 5 cm steps redraws at most one face a frame and far fewer than one
// a frame overall, while every face always covers its slice of the frustum; a few millimetres
// redraw nothing; a cut to elsewhere redraws in that frame every face whose window moved.
TEST(Cascades, FacesAreReusedUntilTheCameraMovesAMargin) {
  const PoleField f;
  ShadowMap map;
  CascadeFaces fit;
  const auto update = [&](Vec3 eye) {
    const View camera = View::perspective_view(eye, f.camera.forward, {0, 1, 0}, radians(60.0f), {320, 180});
    fit = fit_cascades(camera, 0.4f, 200.0f, f.sun, f.bounds, 4, 512);
    return update_cascaded_shadow_map(f.raster, fit, camera, -1, map);
  };
  const auto all_cover = [&] {
    for (size_t i = 0; i < fit.faces.size(); ++i)
      if (!covers(map.faces[i], fit.needed[i])) return false;
    return true;
  };
  EXPECT_EQ(update({0, 1.7f, 0}), 4);
  EXPECT_EQ(update({0.003f, 1.7f, -0.002f}), 0);
  int redrawn = 0;
  for (int step = 1; step <= 60; ++step) {
    const int n = update({0.04f * float(step), 1.7f, -0.03f * float(step)});
    EXPECT_LE(n, 1) << step;
    EXPECT_TRUE(all_cover()) << step;
    redrawn += n;
  }
  std::printf("walking 3 m in 60 frames: %d faces redrawn\n", redrawn);
  EXPECT_GT(redrawn, 0);
  EXPECT_LT(redrawn, 20);
  const CascadeFaces before = fit;
  const int cut = update({40.0f, 1.7f, 30.0f});
  int moved = 0;
  for (size_t i = 0; i < fit.faces.size(); ++i) moved += !(fit.faces[i].eye == before.faces[i].eye);
  EXPECT_EQ(cut, moved);
  EXPECT_GE(cut, 3);  // the farthest may cover the whole ground from both places
  EXPECT_TRUE(all_cover());
}

}  // namespace
}  // namespace caligo

namespace caligo {
namespace {

// In a small scene the far cascades, clipped to it at half the map's size, would be coarser
// than the one face over the scene: they give way to that face, and the nearest are kept.
TEST(Cascades, NeverCoarserThanTheWholeSceneFace) {
  const PoleField f;
  const View whole = fit_directional_face(f.bounds, f.sun, 4096);  // 200 m at 4096: 5 cm texels
  CascadeFaces fit = fit_cascades(f.camera, 0.4f, 200.0f, f.sun, f.bounds, 4, 512);
  const float last_far = fit.far.back();
  end_with_whole_face(fit, whole);
  ASSERT_GE(fit.faces.size(), 2u);
  ASSERT_LT(fit.faces.size(), 4u);
  EXPECT_EQ(fit.faces.back().half_width, whole.half_width);
  EXPECT_EQ(fit.far.back(), last_far);
  for (size_t i = 0; i + 1 < fit.faces.size(); ++i)
    EXPECT_LT(2.0f * std::max(fit.faces[i].half_width, fit.faces[i].half_height) / 512.0f,
              2.0f * std::max(whole.half_width, whole.half_height) / 4096.0f);
  EXPECT_EQ(fit.needed.size(), fit.faces.size());
  EXPECT_TRUE(covers(fit.faces.back(), fit.needed.back()));
}

}  // namespace
}  // namespace caligo
