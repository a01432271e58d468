// The software rasteriser against Embree primary rays, against itself (SIMD vs scalar),
// and against closed-form depths (near-plane clipping, watertightness).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>

#include "realtime/scene_buffers.h"
#include "realtime/test_scenes.h"
#include "scene/camera.h"

namespace caligo {
namespace {

View camera_view(const Scene& scene, Vec2i res) { return View::from_camera(scene.camera(res), res); }

struct Agreement {
  int pixels = 0, coverage_agree = 0, depth_agree = 0, normal_agree = 0, material_agree = 0, both_hit = 0;
};

Agreement compare(const GBuffer& a, const GBuffer& b, float relative_tolerance) {
  Agreement r;
  for (size_t i = 0; i < a.depth.data.size(); ++i) {
    ++r.pixels;
    const bool ha = a.depth.data[i] < kSkyDepth, hb = b.depth.data[i] < kSkyDepth;
    if (ha != hb) continue;
    ++r.coverage_agree;
    if (!ha) {
      ++r.depth_agree, ++r.normal_agree, ++r.material_agree;
      continue;
    }
    ++r.both_hit;
    if (std::abs(a.depth.data[i] - b.depth.data[i]) <= relative_tolerance * b.depth.data[i]) ++r.depth_agree;
    const float d = a.nx.data[i] * b.nx.data[i] + a.ny.data[i] * b.ny.data[i] + a.nz.data[i] * b.nz.data[i];
    if (d > 0.99f) ++r.normal_agree;
    if (a.material[i] == b.material[i] && a.front[i] == b.front[i]) ++r.material_agree;
  }
  return r;
}

// Depth within 0.3 % (the sphere's tessellation: 0.0024 R sagitta at R = 0.8 and ~6 m is
// 3e-4 relative; silhouettes and box edges differ by a pixel) at >= 99 % of pixels.
TEST(Raster, AgreesWithEmbreePerspectiveAndOrthographic) {
  const auto scene = Scene::build(test_scenes::box_sphere_quad());
  const RasterScene raster = RasterScene::build(*scene);
  const View views[2] = {camera_view(*scene, {320, 240}),
                         View::orthographic_view({0.3f, 5, 2}, normalize(Vec3{-0.1f, -1, -0.4f}), {0, 0, -1},
                                                 4.0f, 3.5f, {256, 224})};
  for (const View& view : views) {
    const GBuffer r = rasterize_gbuffer(raster, view);
    const GBuffer t = trace_gbuffer(*scene, view);
    const Agreement a = compare(r, t, 3e-3f);
    const double n = a.pixels;
    std::printf("raster vs embree (%s): coverage %.4f depth %.4f normal %.4f material %.4f of %d pixels\n",
                view.projection == Projection::perspective ? "perspective" : "orthographic",
                a.coverage_agree / n, a.depth_agree / n, a.normal_agree / n, a.material_agree / n, a.pixels);
    EXPECT_GT(a.both_hit, 0.5 * n);
    EXPECT_GE(a.coverage_agree / n, 0.99);
    EXPECT_GE(a.depth_agree / n, 0.99);
    EXPECT_GE(a.normal_agree / n, 0.99);
    EXPECT_GE(a.material_agree / n, 0.99);
  }
}

TEST(Raster, SimdAndScalarGiveIdenticalBuffers) {
  const auto scene = Scene::build(test_scenes::box_sphere_quad());
  const RasterScene raster = RasterScene::build(*scene);
  // An odd size (padding lanes), and a camera close enough that triangles cross the near plane.
  const View views[2] = {
      camera_view(*scene, {333, 217}),
      View::perspective_view({-0.6f, 0.6f, 0.4f}, {1, -0.3f, -0.2f}, {0, 1, 0}, 1.6f, {201, 150})};
  for (const View& view : views) {
    const GBuffer s = rasterize_gbuffer(raster, view, true);
    const GBuffer c = rasterize_gbuffer(raster, view, false);
    EXPECT_EQ(0, std::memcmp(s.depth.data.data(), c.depth.data.data(), s.depth.data.size() * sizeof(float)));
    EXPECT_EQ(0, std::memcmp(s.nx.data.data(), c.nx.data.data(), s.nx.data.size() * sizeof(float)));
    EXPECT_EQ(0, std::memcmp(s.nz.data.data(), c.nz.data.data(), s.nz.data.size() * sizeof(float)));
    EXPECT_EQ(s.material, c.material);
    EXPECT_EQ(s.front, c.front);
    const Plane ds = rasterize_depth(raster, view, true), dc = rasterize_depth(raster, view, false);
    EXPECT_EQ(ds.data, s.depth.data);
    EXPECT_EQ(dc.data, s.depth.data);
  }
}

RasterScene grid_mesh(int n, float jitter_amplitude) {
  RasterScene raster;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> jitter(-jitter_amplitude, jitter_amplitude);
  std::vector<Vec3> grid;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const bool border = i == 0 || j == 0 || i == n || j == n;
      const float a = border ? 0.0f : jitter_amplitude;
      grid.push_back({-2.0f + 4.0f * float(i) / float(n) + (a > 0 ? jitter(rng) : 0.0f),
                      -2.0f + 4.0f * float(j) / float(n) + (a > 0 ? jitter(rng) : 0.0f),
                      a > 0 ? jitter(rng) : 0.0f});
    }
  const Vec3 nz{0, 0, 1};
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Vec3 a = grid[size_t(j * (n + 1) + i)], b = grid[size_t(j * (n + 1) + i + 1)];
      const Vec3 c = grid[size_t((j + 1) * (n + 1) + i)], d = grid[size_t((j + 1) * (n + 1) + i + 1)];
      raster.add_triangle(a, b, d, nz, nz, nz, 0);
      raster.add_triangle(a, d, c, nz, nz, nz, 0);
    }
  return raster;
}

int holes(const RasterScene& raster, const View& view, bool simd) {
  int count = 0;
  for (float d : rasterize_depth(raster, view, simd).data) count += d >= kSkyDepth;
  return count;
}

// Grids of 2 x 32 x 32 triangles fill the view: any crack would show the sky. The jittered
// one is seen in perspective; the regular one orthographically with every coordinate a
// power-of-two fraction, so its edges pass exactly through pixel centres (e == 0, where
// the tie rule alone decides).
TEST(Raster, SharedEdgesLeaveNoCracks) {
  const RasterScene jittered = grid_mesh(32, 0.02f), regular = grid_mesh(32, 0.0f);
  const View perspective =
      View::perspective_view({0.1f, 0.05f, 3}, {0.02f, 0.01f, -1}, {0, 1, 0}, 0.6f, {300, 300});
  const View exact =
      View::orthographic_view({1.0f / 128, 1.0f / 128, 1}, {0, 0, -1}, {0, 1, 0}, 1.5f, 1.5f, {192, 192});
  for (bool simd : {true, false}) {
    EXPECT_EQ(holes(jittered, perspective, simd), 0);
    EXPECT_EQ(holes(regular, exact, simd), 0);
  }
}

// One triangle on the floor y = 0 with a vertex behind the camera: after clipping every
// pixel whose ray meets it gets the analytic depth.
TEST(Raster, TriangleCrossingTheCameraPlaneIsClipped) {
  RasterScene raster;
  const Vec3 a{-50, 0, 10}, b{50, 0, 10}, c{0, 0, -50};
  const Vec3 up{0, 1, 0};
  raster.add_triangle(a, b, c, up, up, up, 0);
  const View view = View::perspective_view({0, 1, 0}, {0, -0.3f, -1}, {0, 1, 0}, 1.2f, {160, 120});
  for (bool simd : {true, false}) {
    const Plane depth = rasterize_depth(raster, view, simd);
    int checked = 0, wrong = 0;
    for (int y = 0; y < 120; ++y)
      for (int x = 0; x < 160; ++x) {
        const Ray ray = view.ray({float(x) + 0.5f, float(y) + 0.5f});
        float expected = kSkyDepth;
        if (ray.direction.y < 0.0f) {
          const float t = -ray.origin.y / ray.direction.y;
          const Vec3 p = ray.at(t);
          // Inside the triangle (x, z)?
          auto side = [&](Vec3 u, Vec3 v) { return (v.x - u.x) * (p.z - u.z) - (v.z - u.z) * (p.x - u.x); };
          const float s0 = side(a, b), s1 = side(b, c), s2 = side(c, a);
          if ((s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0))
            expected = t * view.depth_per_t(ray.direction);
        }
        ++checked;
        const float got = depth.at(x, y);
        if (expected >= kSkyDepth ? got < kSkyDepth : std::abs(got - expected) > 1e-4f * expected) ++wrong;
      }
    // The triangle's far corner (50 m away) is a few pixels wide: allow its edge pixels.
    std::printf("near-plane clipping (simd %d): %d of %d pixels off\n", int(simd), wrong, checked);
    EXPECT_LE(wrong, checked / 200) << "simd " << simd;
    int covered = 0;
    for (float d : depth.data) covered += d < kSkyDepth;
    EXPECT_GT(covered, checked / 3);  // the floor below the horizon is there
  }
}

}  // namespace
}  // namespace caligo
