// The real-time pipeline against the path tracer's single-scattering reference
// (--max-depth 1 --max-volume-bounces 1): at full resolution, without interleaving, gather
// or history and with many march steps, the two solve the same integral with the same light
// models, so they must agree: the means within 4 standard errors of the reference's own mean
// (from its per-pixel variance), and 5 % relative RMSE (the pixels carry the reference's noise).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "realtime/pipeline.h"
#include "scene/scene.h"
#include "realtime/reference_compare.h"
#include "render/render.h"
#include "settings/aov.h"
#include "scene/scene_parser.h"

namespace caligo {
namespace {

// The reference's spp. Measured (2026-12) on these six lights: RMSE/mean 0.4-3.0 % (mostly the
// reference's pixel noise), a standard error of the image mean of 0.03-0.11 %, and mean errors
// of 0.02-0.14 %, at most 1.4 standard errors (the former tolerance, 2 %, was 15-100x them).
constexpr int kReferenceSpp = 2048;

// The standard error of the image's mean (channel average), relative to the mean, from the
// variance of each pixel's mean (the variance AOV; channels averaged, an upper bound when they
// are correlated).
double relative_standard_error(const Image& image) {
  const int vr = image.channel_index("variance.R"), vg = image.channel_index("variance.G"),
            vb = image.channel_index("variance.B");
  double variance = 0.0, mean = 0.0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      variance += (double(image.at(x, y, vr)) + image.at(x, y, vg) + image.at(x, y, vb)) / 3.0;
      mean += image.rgb(x, y, 0).average();
    }
  const double n = double(image.width()) * image.height();
  return std::sqrt(variance) / n / (mean / n);
}

std::string scene_with(const std::string& light) {
  return R"({
    "camera": {"position": [0, 1.6, 6], "look_at": [0, 1.0, 0], "fov": 50, "resolution": [48, 36]},
    "materials": {"grey": {"type": "diffuse", "reflectance": 0.5}},
    "shapes": [
      {"type": "rectangle", "corner": [-6, 0, -6], "edge1": [0, 0, 12], "edge2": [12, 0, 0], "material": "grey"},
      {"type": "box", "min": [-0.5, 0, -0.5], "max": [0.5, 1.2, 0.5], "material": "grey"}
    ],
    "lights": [)" + light + R"(],
    "media": {"fog": {"sigma_s": 0.15, "sigma_a": 0.02, "phase": {"type": "hg", "g": 0.3}}},
    "volumes": [{"type": "box", "min": [-6, 0, -6], "max": [6, 5, 6], "medium": "fog"}]
  })";
}

// The path tracer averages each pixel's area; the real-time frame samples pixel centres.
// Rendering the real-time frame at kSupersample^2 times the pixels and averaging makes both
// estimate the same pixel integral, so edges do not count as disagreement.
constexpr int kSupersample = 8;

Image box_downsample(const Image& image, int factor) {
  Image out(image.width() / factor, image.height() / factor, {"R", "G", "B"});
  for (int y = 0; y < out.height(); ++y)
    for (int x = 0; x < out.width(); ++x) {
      RGB sum;
      for (int j = 0; j < factor; ++j)
        for (int i = 0; i < factor; ++i) sum += image.rgb(x * factor + i, y * factor + j, 0);
      out.set_rgb(x, y, 0, sum / float(factor * factor));
    }
  return out;
}

void expect_agreement(const std::string& light) {
  const SceneDesc desc = parse_scene_text(scene_with(light), "agreement-test", CALIGO_SCENES_DIR);
  RealtimeSettings s = realtime_settings(desc);
  s.resolution = {desc.camera.resolution.x * kSupersample, desc.camera.resolution.y * kSupersample};
  s.scale = 1;
  s.accumulation.tile_size = 1;
  s.accumulation.samples = 256;
  s.gather_radius = 0;
  s.temporal = false;
  RealtimePipeline pipeline(Scene::build(desc), s);
  const Image realtime = box_downsample(to_image(pipeline.render(0.0f, 0).color), kSupersample);

  const auto scene = Scene::build(desc);
  RenderSettings rs = render_settings(desc);
  rs.spp = kReferenceSpp;
  rs.path.limits.max_bounces = 1;
  rs.path.limits.max_volume_bounces = 1;
  rs.aovs = AovSet{}.with(Aov::kVariance);
  const Image reference = render(*scene, rs).image;

  const ReferenceError err = reference_error(realtime, reference);
  const double se = relative_standard_error(reference);
  std::printf("mean error %+.3f %% (reference standard error %.3f %%), relative RMSE %.3f %%, RMSE/mean %.3f %%\n",
              err.mean_error * 100, se * 100, err.relative_rmse * 100, err.rmse_over_mean * 100);
  EXPECT_LT(std::abs(err.mean_error), 4.0 * se) << light;
  EXPECT_LT(err.rmse_over_mean, 0.05) << light;
}

TEST(RealtimeAgreement, PointLight) {
  expect_agreement(R"({"type": "point", "position": [1.5, 4.5, 1], "intensity": 12})");
}

TEST(RealtimeAgreement, SpotLight) {
  expect_agreement(R"({"type": "spot", "position": [-2, 4.8, 1], "look_at": [0, 0, 0], "inner_angle": 25,
                       "outer_angle": 35, "intensity": 30})");
}

TEST(RealtimeAgreement, BoxLight) {
  expect_agreement(R"({"type": "box", "position": [0, 4.9, 1], "direction": [0.2, -1, 0], "up": [0, 0, 1],
                       "width": 5, "height": 5, "range": 6, "irradiance": 1.5})");
}

// The gobo and the IES profile go through the same light_profile.h functions in both.
TEST(RealtimeAgreement, SpotLightWithGobo) {
  expect_agreement(R"({"type": "spot", "position": [-2, 4.8, 1], "look_at": [0, 0, 0], "inner_angle": 25,
                       "outer_angle": 35, "intensity": 30, "gobo": {"file": "assets/stained-glass.png"}})");
}

TEST(RealtimeAgreement, PointLightWithIes) {
  expect_agreement(R"({"type": "point", "position": [1.5, 4.5, 1], "intensity": 12,
                       "ies": {"file": "assets/wall-wash.ies", "axis": [0, -1, 0]}})");
}

TEST(RealtimeAgreement, DirectionalLight) {
  expect_agreement(R"({"type": "directional", "direction": [-0.4, -1, -0.3], "irradiance": 1.2})");
}

}  // namespace
}  // namespace caligo
