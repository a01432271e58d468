// The light samplers are unbiased in the path tracer: a small scene with 21 lights of every
// finite kind (points, spots, one-sided quads, spheres) and a sky, over a diffuse floor and a
// box in haze, rendered with tree, power and uniform light selection. MIS weights of BSDF- and
// phase-sampled hits on the quads and spheres use each sampler's pmf at the previous vertex
// (the surface point, or the medium segment), so a pmf that disagreed with the choice made
// by next-event estimation would bias the mean. Each sampler renders kRuns independent images
// (different seeds); the standard error of the image mean is the spread of the kRuns means /
// sqrt(kRuns), and the samplers' means must agree within 4 combined standard errors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "render/render.h"
#include "scene/builtins.h"

namespace caligo {
namespace {

constexpr int kRuns = 8;

std::string twenty_lights_scene() {
  std::string json = R"json({
  "camera": {"position": [0, 2.5, 7], "look_at": [0, 1, 0], "fov": 50, "resolution": [16, 12]},
  "render": {"spp": 64, "max_depth": 3, "max_volume_bounces": 3},
  "materials": {"floor": {"type": "diffuse", "reflectance": 0.6}, "box": {"type": "diffuse", "reflectance": 0.4}},
  "media": {"haze": {"sigma_s": 0.12, "sigma_a": 0.01}},
  "volumes": [{"type": "box", "min": [-5, 0, -5], "max": [5, 5, 5], "medium": "haze"}],
  "shapes": [
    {"type": "rectangle", "corner": [-5, 0, 5], "edge1": [10, 0, 0], "edge2": [0, 0, -10], "material": "floor"},
    {"type": "box", "min": [-0.8, 0, -0.8], "max": [0.8, 1.4, 0.8], "material": "box"}
  ],
  "lights": [
    {"type": "environment", "radiance": 0.02},
    {"type": "quad", "corner": [-3, 4.5, -3], "edge1": [1, 0, 0], "edge2": [0, 0, 1], "radiance": 6},
    {"type": "quad", "corner": [2, 4.5, 1], "edge1": [0, 0, 1.2], "edge2": [0.8, 0, 0], "radiance": 4},
    {"type": "sphere", "center": [2, 1, -1.5], "radius": 0.3, "radiance": 5},
    {"type": "sphere", "center": [-2.2, 2.5, 1], "radius": 0.25, "radiance": 8})json";
  for (int i = 0; i < 13; ++i) {
    const float x = -4.0f + 0.65f * float(i), z = (i % 2 ? -3.0f : 2.0f) + 0.3f * float(i % 5);
    const float y = 1.0f + 0.25f * float(i % 7);
    char buf[160];
    std::snprintf(buf, sizeof buf, ",\n    {\"type\": \"point\", \"position\": [%g, %g, %g], \"intensity\": %g}", x, y, z,
                  0.3 + 0.2 * (i % 4));
    json += buf;
  }
  for (int i = 0; i < 4; ++i) {
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  ",\n    {\"type\": \"spot\", \"position\": [%g, 4, %g], \"look_at\": [%g, 0, %g], \"inner_angle\": 15, "
                  "\"outer_angle\": 25, \"intensity\": 6}",
                  -3.0f + 2.0f * float(i), 0.5f * float(i) - 1.0f, -2.5f + 2.0f * float(i), 0.5f * float(i) - 1.5f);
    json += buf;
  }
  return json + "\n  ]\n}\n";
}

struct Estimate {
  double mean, standard_error;
};

Estimate image_mean(const Scene& scene, const SceneDesc& desc, LightSamplerKind kind) {
  double sum = 0.0, sum_sq = 0.0;
  for (int run = 0; run < kRuns; ++run) {
    RenderSettings s = render_settings(desc);
    s.path.light_sampler = kind;
    s.seed = uint64_t(1000 + run);
    const Image image = render(scene, s).image;
    double m = 0.0;
    for (int y = 0; y < image.height(); ++y)
      for (int x = 0; x < image.width(); ++x) m += image.rgb(x, y, 0).average();
    m /= double(image.width() * image.height());
    sum += m;
    sum_sq += m * m;
  }
  const double mean = sum / kRuns;
  const double variance = (sum_sq - kRuns * mean * mean) / (kRuns - 1);
  return {mean, std::sqrt(std::max(0.0, variance) / kRuns)};
}

TEST(LightTreeRender, TreePowerAndUniformAgreeWithinTheirStandardErrors) {
  const SceneDesc desc = parse_builtin(BuiltinScene{"twenty-lights", "", twenty_lights_scene()});
  ASSERT_EQ(desc.lights.size(), 22u);
  const auto scene = Scene::build(desc);
  const Estimate uniform = image_mean(*scene, desc, LightSamplerKind::kUniform);
  const Estimate power = image_mean(*scene, desc, LightSamplerKind::kPower);
  const Estimate tree = image_mean(*scene, desc, LightSamplerKind::kTree);
  std::printf("image mean: uniform %.5f +- %.5f, power %.5f +- %.5f, tree %.5f +- %.5f\n", uniform.mean,
              uniform.standard_error, power.mean, power.standard_error, tree.mean, tree.standard_error);
  ASSERT_GT(uniform.mean, 0.01);
  EXPECT_LT(uniform.standard_error, 0.02 * uniform.mean);  // the test can see a 10 % bias
  const auto agree = [](Estimate a, Estimate b) {
    return std::abs(a.mean - b.mean) < 4.0 * std::hypot(a.standard_error, b.standard_error);
  };
  EXPECT_TRUE(agree(tree, uniform));
  EXPECT_TRUE(agree(power, uniform));
  EXPECT_TRUE(agree(tree, power));
}

// With one light every strategy chooses it with probability 1: tree and power images are equal
// to the bit (the tree as default changes nothing in single-light scenes).
TEST(LightTreeRender, OneLightScenesAreIdenticalUnderTreeAndPower) {
  for (const char* name : {"lamp-in-fog", "spot-shafts"}) {
    const SceneDesc desc = parse_builtin(*find_builtin(name));
    const auto scene = Scene::build(desc);
    RenderSettings s = render_settings(desc);
    s.resolution = {16, 12};
    s.spp = 4;
    s.path.light_sampler = LightSamplerKind::kPower;
    const Image power = render(*scene, s).image;
    s.path.light_sampler = LightSamplerKind::kTree;
    const Image tree = render(*scene, s).image;
    for (int y = 0; y < 12; ++y)
      for (int x = 0; x < 16; ++x) {
        const RGB a = power.rgb(x, y, 0), b = tree.rgb(x, y, 0);
        ASSERT_TRUE(a.r == b.r && a.g == b.g && a.b == b.b) << name << " pixel " << x << "," << y;
      }
  }
}

}  // namespace
}  // namespace caligo
