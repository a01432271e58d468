// Path guiding, adaptive sampling and the sample clamp through the render loop: guided renders
// converge to the unguided mean, are the same bit for bit for any thread count and across a
// resume in the middle of training; adaptive sampling stops converged pixels at the minimum and
// stays unbiased; a clamp bounds what it says.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "core/test_stat.h"
#include "render/render.h"
#include "scene/builtins.h"
#include "scene/scene_parser.h"
#include "scene/scene.h"

namespace caligo {
namespace {

using testing::Stat;

struct Builtin {
  std::unique_ptr<Scene> scene;
  RenderSettings settings;
  explicit Builtin(const char* name, Vec2i resolution, int spp) {
    const SceneDesc desc = parse_builtin(*find_builtin(name));
    scene = Scene::build(desc);
    settings = render_settings(desc);
    settings.resolution = resolution;
    settings.spp = spp;
  }
};

double image_mean(const Image& image) {
  double sum = 0.0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) sum += image.rgb(x, y, 0).average();
  return sum / (double(image.width()) * image.height());
}

// Guided and unguided renders of one scene: the image means over `seeds` independent renders
// each (a guided render's field is trained afresh every time, so each seed is one draw of the
// whole estimator) agree within 4 standard errors of their difference.
void expect_guided_mean_agrees(const char* name, Vec2i resolution, int spp, int seeds, bool distances = false) {
  Builtin b(name, resolution, spp);
  b.settings.path.guided_distances = distances;
  Stat guided, unguided;
  for (int seed = 0; seed < seeds; ++seed) {
    b.settings.seed = uint64_t(seed + 1);
    b.settings.path.guiding = GuidingMode::kOff;
    unguided.add(image_mean(render(*b.scene, b.settings).image));
    b.settings.path.guiding = GuidingMode::kAll;
    guided.add(image_mean(render(*b.scene, b.settings).image));
  }
  const double se = std::hypot(guided.se(), unguided.se());
  std::printf("%s: guided %.5f unguided %.5f, standard error of the difference %.2g\n", name, guided.mean(),
              unguided.mean(), se);
  EXPECT_LT(std::abs(guided.mean() - unguided.mean()), 4.0 * se) << name;
  EXPECT_LT(se, 0.02 * unguided.mean()) << name << ": too noisy to show a bias";
}

TEST(GuidedRender, LampInFogConvergesToTheUnguidedMean) { expect_guided_mean_agrees("lamp-in-fog", {24, 18}, 64, 10); }
// Guided distances too (PathSettings::guided_distances): the fluence mixture along each segment.
TEST(GuidedRender, GuidedDistancesConvergeToTheUnguidedMean) {
  expect_guided_mean_agrees("lamp-in-fog", {24, 18}, 64, 10, true);
}
TEST(GuidedRender, CloudConvergesToTheUnguidedMean) { expect_guided_mean_agrees("cloud", {24, 18}, 32, 8); }
TEST(GuidedRender, DefaultConvergesToTheUnguidedMean) { expect_guided_mean_agrees("default", {24, 18}, 64, 8); }
TEST(GuidedRender, NestedMediaConvergeToTheUnguidedMean) {
  expect_guided_mean_agrees("glass-of-water", {24, 18}, 32, 8);
}

// A dense, bright medium inside a dielectric: hundreds of guided medium events per path.
TEST(GuidedRender, SubsurfaceConvergesToTheUnguidedMean) { expect_guided_mean_agrees("sss", {24, 18}, 32, 8); }

TEST(GuidedRender, TheFieldLearnsAndIsReported) {
  Builtin b("lamp-in-fog", {32, 24}, 16);
  b.settings.path.guiding = GuidingMode::kVolume;
  const RenderStats stats = render(*b.scene, b.settings).stats;
  EXPECT_EQ(stats.guiding.iterations, 4);  // samples 0, 1-2, 3-6, 7-14 trained; 15 used the field
  EXPECT_GT(stats.guiding.leaves, 1u);
  EXPECT_GT(stats.guiding.nodes, stats.guiding.leaves);
  EXPECT_GT(stats.guiding.bytes, 0u);
}

TEST(GuidedRender, ImagesAreTheSameForAnyThreadCount) {
  Builtin b("lamp-in-fog", {24, 18}, 12);
  b.settings.path.guiding = GuidingMode::kAll;
  b.settings.threads = 1;
  Film one(b.settings.resolution, b.settings.aovs);
  render_up_to(one, *b.scene, b.settings, b.settings.spp);
  b.settings.threads = 2;
  b.settings.tile_size = 5;  // other tiles, other interleavings of the training sums
  Film two(b.settings.resolution, b.settings.aovs);
  render_up_to(two, *b.scene, b.settings, b.settings.spp);
  EXPECT_FALSE(one.training_state().empty());
  EXPECT_TRUE(one == two);
}

// A checkpoint in the middle of training iteration 2 (samples 3 to 6), saved and loaded as bytes
// with the field in it, resumed to 12: the film one render to 12 leaves, bit for bit.
TEST(GuidedRender, AResumeInTheMiddleOfTrainingIsExact) {
  Builtin b("lamp-in-fog", {24, 18}, 12);
  b.settings.path.guiding = GuidingMode::kAll;
  Film once(b.settings.resolution, b.settings.aovs);
  render_up_to(once, *b.scene, b.settings, 12);
  Film first(b.settings.resolution, b.settings.aovs);
  render_up_to(first, *b.scene, b.settings, 5);
  Film resumed = Film::from_bytes(first.to_bytes(), "checkpoint");
  render_up_to(resumed, *b.scene, b.settings, 12);
  EXPECT_TRUE(resumed == once);
  // A stop before the pass's first pixel does not end the training iteration it is in.
  Film stopped(b.settings.resolution, b.settings.aovs);
  std::atomic<bool> stop{false};
  render_up_to(stopped, *b.scene, b.settings, 2);
  stop = true;
  render_up_to(stopped, *b.scene, b.settings, 12, &stop);  // stops before any pixel
  stop = false;
  render_up_to(stopped, *b.scene, b.settings, 12);
  EXPECT_TRUE(stopped == once);
}

TEST(GuidedRender, UnguidedRendersKeepNoTrainingState) {
  Builtin b("lamp-in-fog", {8, 6}, 4);
  Film film(b.settings.resolution, b.settings.aovs);
  render_up_to(film, *b.scene, b.settings, 4);
  EXPECT_TRUE(film.training_state().empty());
}

// A lamp in a fog sphere under a uniform sky: the sky's pixels have no variance and stop at the
// minimum; pixels through the fog take more. The image mean over seeds stays within 4 standard
// errors of the mean of full renders.
TEST(AdaptiveSampling, ConvergedPixelsStopAtTheMinimumAndTheMeanHolds) {
  Builtin b("lamp-in-fog", {24, 18}, 256);
  {
    const SceneDesc desc = parse_scene_text(R"json({
      "camera": {"position": [0, 0, 6], "look_at": [0, 0, 0], "fov": 60, "resolution": [24, 18]},
      "media": {"fog": {"sigma_s": 0.4, "sigma_a": 0.02, "phase": {"type": "hg", "g": 0.3}}},
      "volumes": [{"type": "sphere", "center": [0, 0, 0], "radius": 2, "medium": "fog"}],
      "lights": [{"type": "point", "position": [0.4, 0.2, 0.3], "intensity": 10},
                 {"type": "environment", "radiance": 0.2}]})json",
                                            "sky-and-fog", ".");
    b.scene = Scene::build(desc);
  }
  const float sky = 0.2f;
  b.settings.aovs = b.settings.aovs.with(Aov::kVariance).with(Aov::kSamples);
  Stat adaptive, full;
  int at_minimum = 0, above = 0;
  for (int seed = 0; seed < 6; ++seed) {
    b.settings.seed = uint64_t(seed + 1);
    b.settings.adaptive = {};
    full.add(image_mean(render(*b.scene, b.settings).image));
    b.settings.adaptive = {.threshold = 0.05f, .min_samples = 16};
    const Image image = render(*b.scene, b.settings).image;
    adaptive.add(image_mean(image));
    const int samples = image.channel_index("samples");
    ASSERT_GE(samples, 0);
    for (int y = 0; y < image.height(); ++y)
      for (int x = 0; x < image.width(); ++x) {
        const float n = image.at(x, y, samples);
        EXPECT_GE(n, 16.0f);
        EXPECT_LE(n, 256.0f);
        const bool sees_sky = std::abs(image.rgb(x, y, 0).r - sky) < 1e-6f;
        if (sees_sky) {
          EXPECT_EQ(n, 16.0f) << x << ", " << y;
        }
        at_minimum += sees_sky && n == 16.0f;
        above += n > 64.0f;
      }
  }
  EXPECT_GT(at_minimum, 0);
  EXPECT_GT(above, 0);
  const double se = std::hypot(adaptive.se(), full.se());
  EXPECT_LT(std::abs(adaptive.mean() - full.mean()), 4.0 * se);
  EXPECT_LT(se, 0.02 * full.mean());
}

TEST(AdaptiveSampling, ImagesAreTheSameForAnyThreadCountAndPassSplit) {
  Builtin b("lamp-in-fog", {24, 18}, 64);
  b.settings.aovs = b.settings.aovs.with(Aov::kVariance);
  b.settings.adaptive = {.threshold = 0.1f, .min_samples = 8};
  b.settings.threads = 1;
  Film one(b.settings.resolution, b.settings.aovs);
  render_up_to(one, *b.scene, b.settings, 64);
  b.settings.threads = 2;
  Film passes(b.settings.resolution, b.settings.aovs);
  for (int target : {3, 9, 20, 64}) render_up_to(passes, *b.scene, b.settings, target);
  EXPECT_TRUE(one == passes);
}

// Every sample's direct and indirect light is bounded, so every pixel's mean is: beauty <=
// direct limit + indirect limit, and the indirect layers alone <= the indirect limit.
TEST(SampleClamp, BoundsEverySample) {
  Builtin b("lamp-in-fog", {24, 18}, 16);
  b.settings.aovs = AovSet::parse("lights");
  b.settings.clamp = {.direct = 0.3f, .indirect = 0.05f};
  const Image image = render(*b.scene, b.settings).image;
  const int indirect = image.channel_index("volume_indirect.R");
  ASSERT_GE(indirect, 0);
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      EXPECT_LE(image.rgb(x, y, 0).max_component(), 0.35f + 1e-5f);
      for (int c = 0; c < 3; ++c) EXPECT_LE(image.at(x, y, indirect + c), 0.05f + 1e-6f);
    }
  b.settings.clamp = {};
  const Image unclamped = render(*b.scene, b.settings).image;
  float peak = 0.0f;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) peak = std::max(peak, unclamped.rgb(x, y, 0).max_component());
  EXPECT_GT(peak, 0.35f);  // the clamp had something to cut
}

}  // namespace
}  // namespace caligo
