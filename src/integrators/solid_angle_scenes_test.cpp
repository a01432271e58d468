// Whole-image checks of solid-angle sampling of quad lights and of equiangular sampling
// clipped to where a light reaches (lights/area_light_sampling.h, lights/light_reach.h):
// the renderer's mean is unchanged against the old sampling, within the standard error,
// and the variance drops.
//
// Every scene is seen through a camera of 0.01 degree field of view, so all its pixels
// estimate the same value: the pixels are independent estimates (each from its own sample
// sequence), their spread gives the per-pixel variance and the standard error of the mean,
// SE = sd(pixels) / sqrt(pixels). Two means agree when they differ by less than
// 4 sqrt(SE_a^2 + SE_b^2) (false alarm ~6e-5 per comparison for Gaussian errors).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "lights/area_light_sampling.h"
#include "render/render.h"
#include "scene/mesh_loader.h"
#include "scene/builtins.h"
#include "scene/scene_parser.h"

namespace caligo {
namespace {

struct PixelStats {
  double mean = 0.0, variance = 0.0, se = 0.0;  // over pixels; variance of one pixel
};

PixelStats render_stats(const std::string& json, int spp, LightSamplingOptions options, DistanceSampling sampling,
                        int max_bounces = 1) {
  const SceneDesc desc = parse_scene_text(json, "test", "");
  const auto scene = Scene::build(desc);
  RenderSettings s = render_settings(desc);
  s.spp = spp;
  s.path.limits.max_bounces = max_bounces;
  s.path.limits.max_volume_bounces = 1;
  s.path.distance_sampling = sampling;
  set_light_sampling_options(options);
  const Image image = render(*scene, s).image;
  set_light_sampling_options({});
  const int n = image.width() * image.height();
  double sum = 0.0, sum2 = 0.0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      const double v = image.rgb(x, y, 0).g;
      sum += v;
      sum2 += v * v;
    }
  PixelStats st;
  st.mean = sum / n;
  st.variance = (sum2 - sum * st.mean) / (n - 1);
  st.se = std::sqrt(st.variance / n);
  return st;
}

void expect_same_mean(const PixelStats& a, const PixelStats& b) {
  EXPECT_NEAR(a.mean, b.mean, 4.0 * std::sqrt(a.se * a.se + b.se * b.se));
}

// A diffuse floor (reflectance 0.5) 0.5 m under a 4 x 4 m quad of radiance 1 facing it,
// seen at the point under the quad's centre from outside (the camera ray passes below it).
constexpr const char* kQuadOverFloor = R"json({
  "camera": {"position": [0, 0.25, 3], "look_at": [0, 0, 0], "fov": 0.01, "resolution": [32, 32]},
  "materials": {"floor": {"type": "diffuse", "reflectance": 0.5}},
  "shapes": [{"type": "rectangle", "corner": [-10, 0, -10], "edge1": [0, 0, 20], "edge2": [20, 0, 0],
              "material": "floor"}],
  "lights": [{"type": "quad", "corner": [-2, 0.5, -2], "edge1": [4, 0, 0], "edge2": [0, 0, 4], "radiance": 1}]
})json";

// Form factor from a point to a parallel a x b rectangle with one corner straight above at
// height h (the classic closed form), times 4 for the centre of a 2a x 2b one.
double centre_form_factor(double a, double b, double h) {
  const double A = a / h, B = b / h;
  const double sa = std::sqrt(1 + A * A), sb = std::sqrt(1 + B * B);
  return 4.0 / (2.0 * M_PI) * (A / sa * std::atan(B / sa) + B / sb * std::atan(A / sb));
}

TEST(SolidAngleScenes, QuadLightOverAFloorKeepsItsMeanAndLosesVariance) {
  const PixelStats area = render_stats(kQuadOverFloor, 4, {.solid_angle = false}, DistanceSampling::kMis);
  const PixelStats solid = render_stats(kQuadOverFloor, 4, {}, DistanceSampling::kMis);
  // Outgoing radiance of the floor: reflectance * L * F (E = pi L F, L_o = rho E / pi).
  const double expected = 0.5 * 1.0 * centre_form_factor(2, 2, 0.5);
  std::printf("quad over floor: expected %.5f, area %.5f +- %.5f, solid angle %.5f +- %.5f, variance ratio "
              "area/solid %.2f\n",
              expected, area.mean, area.se, solid.mean, solid.se, area.variance / solid.variance);
  expect_same_mean(area, solid);
  EXPECT_NEAR(solid.mean, expected, 4.0 * solid.se);
  EXPECT_NEAR(area.mean, expected, 4.0 * area.se);
  EXPECT_LT(solid.variance, area.variance);
}

// A narrow spot (outer cone 6 degrees) shining down through haze; the camera ray crosses the
// beam horizontally 2.4 m below the light, through 8 m of haze. Single scattering.
constexpr const char* kSpotBeam = R"json({
  "camera": {"position": [0, 1.5, 6], "look_at": [0, 1.5, 0], "fov": 0.01, "resolution": [32, 32]},
  "media": {"haze": {"sigma_s": 0.25, "sigma_a": 0.02, "phase": {"type": "hg", "g": 0.5}}},
  "volumes": [{"type": "box", "min": [-4, 0, -4], "max": [4, 4, 4], "medium": "haze"}],
  "lights": [{"type": "spot", "position": [0, 3.9, 0], "look_at": [0, 0, 0], "inner_angle": 4,
              "outer_angle": 6, "intensity": 50}]
})json";

// A one-sided quad light facing down inside haze, the camera ray rising through its plane:
// the part of the ray above the plane gets nothing.
constexpr const char* kQuadInHaze = R"json({
  "camera": {"position": [0, 0.2, 6], "look_at": [0, 2.2, -2], "fov": 0.01, "resolution": [32, 32]},
  "media": {"haze": {"sigma_s": 0.25, "sigma_a": 0.02}},
  "volumes": [{"type": "box", "min": [-4, 0, -4], "max": [4, 4, 4], "medium": "haze"}],
  "lights": [{"type": "quad", "corner": [-0.5, 1.5, -0.5], "edge1": [1, 0, 0], "edge2": [0, 0, 1], "radiance": 20}]
})json";

void compare_clipping(const char* name, const char* json, DistanceSampling sampling, int spp) {
  const PixelStats full = render_stats(json, spp, {.clip_equiangular = false}, sampling);
  const PixelStats clipped = render_stats(json, spp, {}, sampling);
  std::printf("%s: unclipped %.5f +- %.5f, clipped %.5f +- %.5f, variance ratio unclipped/clipped %.2f\n", name,
              full.mean, full.se, clipped.mean, clipped.se, full.variance / clipped.variance);
  ASSERT_GT(clipped.mean, 10.0 * clipped.se);  // the beam is seen
  expect_same_mean(full, clipped);
  EXPECT_LT(clipped.variance, full.variance);
}

TEST(SolidAngleScenes, ClippedEquiangularKeepsTheSpotBeamsMeanAndLosesVariance) {
  compare_clipping("spot beam, MIS", kSpotBeam, DistanceSampling::kMis, 4);
  compare_clipping("spot beam, equiangular", kSpotBeam, DistanceSampling::kEquiangular, 4);
}

TEST(SolidAngleScenes, ClippedEquiangularKeepsTheQuadLightsMeanAndLosesVariance) {
  compare_clipping("quad in haze, MIS", kQuadInHaze, DistanceSampling::kMis, 4);
}

// The built-ins of this work: neon's tubes become 3 x 2,048 triangle lights, each with its
// material's radiance (6 x colour); the stage's Wuson loads with its 3,732 triangles; both
// render finite, non-black images at low resolution.
TEST(SolidAngleScenes, NeonAndStageBuildAndRender) {
  for (const char* name : {"neon", "stage"}) {
    SCOPED_TRACE(name);
    const SceneDesc desc = parse_builtin(*find_builtin(name));
    const auto scene = Scene::build(desc);
    const bool neon = std::string(name) == "neon";
    int per_colour[3] = {0, 0, 0};
    const RGB colours[3] = {RGB(1, 0.15f, 0.6f) * 6.0f, RGB(0.1f, 0.8f, 1) * 6.0f, RGB(1, 0.55f, 0.1f) * 6.0f};
    for (const Light& l : scene->lights())
      if (const auto* t = std::get_if<TriangleLight>(&l))
        for (int c = 0; c < 3; ++c) per_colour[c] += t->radiance == colours[c];
    for (int c = 0; c < 3; ++c) EXPECT_EQ(per_colour[c], neon ? 2048 : 0) << "colour " << c;
    if (!neon) {
      const MeshFileShape& wuson = std::get<MeshFileShape>(desc.shapes[1].geometry);
      EXPECT_EQ(load_mesh(wuson.path, {}).triangle_count(), 3732u);
    }
    RenderSettings s = render_settings(desc);
    s.resolution = {16, 9};
    s.spp = 4;
    const Image image = render(*scene, s).image;
    double sum = 0.0;
    for (int y = 0; y < image.height(); ++y)
      for (int x = 0; x < image.width(); ++x) {
        const RGB v = image.rgb(x, y, 0);
        ASSERT_TRUE(std::isfinite(v.r) && std::isfinite(v.g) && std::isfinite(v.b));
        sum += v.average();
      }
    EXPECT_GT(sum, 0.0);
  }
}

}  // namespace
}  // namespace caligo
