// The film's outputs from real renders: light layers that add up to the beauty and land in the
// layer their path names, alpha behind and inside fog, holdout surfaces and holdout media,
// the orthographic `slab` built-in against Beer-Lambert, a thin lens focused on a plane
// against the pinhole, and a frame split into sample ranges against one render, bit for bit.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <thread>

#include "integrators/test_scenes.h"
#include "render/render.h"
#include "scene/builtins.h"

namespace caligo {
namespace {

using testing::camera_at;

int add_material(SceneDesc& desc, Bsdf bsdf, RGB emission = RGB(0.0f)) {
  desc.materials.push_back({std::to_string(desc.materials.size()), bsdf, emission, false});
  return int(desc.materials.size()) - 1;
}

RenderSettings settings_for(const SceneDesc& desc, int spp, AovSet aovs = AovSet::all()) {
  RenderSettings s = render_settings(desc);
  s.spp = spp;
  s.aovs = aovs;
  return s;
}

RGB layer(const Image& image, int x, int y, LightKind kind) {
  const auto rgb = image.rgb_indices(std::string(aov_name(light_aov(kind))) + ".");
  return rgb ? image.rgb(x, y, *rgb) : RGB(-1.0f);
}

float channel(const Image& image, int x, int y, const char* name) {
  return image.at(x, y, image.channel_index(name));
}

// A floor and a back wall, a fog box with some emission, a point light, an emissive quad and a
// visible sky: every kind of light reaches the camera somewhere.
SceneDesc every_kind_of_light() {
  SceneDesc desc = camera_at({0, 1, 5}, {0, 0.8f, 0}, {24, 16}, 50.0f);
  const int grey = add_material(desc, DiffuseBsdf{RGB(0.6f)});
  desc.shapes.push_back({RectangleShape{{-3, 0, 3}, {6, 0, 0}, {0, 0, -6}}, {}, grey});  // floor, facing up
  desc.shapes.push_back({RectangleShape{{-3, 0, -1.5f}, {6, 0, 0}, {0, 3, 0}}, {}, grey});
  const int lamp = add_material(desc, BlackBsdf{}, RGB(3.0f));
  desc.shapes.push_back({RectangleShape{{1, 2.5f, -1}, {0.6f, 0, 0}, {0, 0, 0.6f}}, {}, lamp});  // facing down
  VolumePrimitive fog{BoxVolumeShape{{}, {-1.5f, 0, -1}, {0.5f, 1.5f, 1}}, {RGB(0.05f), RGB(0.6f), RGB(0.2f)}};
  desc.volumes.push_back(fog);
  desc.lights.push_back(PointLight{{-0.5f, 1.2f, 0.5f}, RGB(2.0f)});
  desc.lights.push_back(EnvironmentLight{RGB(0.3f, 0.4f, 0.6f)});
  return desc;
}

TEST(FilmScenes, LightLayersAddUpToTheBeautyAndEachKindAppears) {
  const SceneDesc desc = every_kind_of_light();
  const auto scene = Scene::build(desc);
  const Image image = render(*scene, settings_for(desc, 8)).image;
  RGB totals[kLightKindCount];
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      RGB sum;
      for (int k = 0; k < kLightKindCount; ++k) {
        const RGB l = layer(image, x, y, LightKind(k));
        sum += l;
        totals[k] += l;
      }
      const RGB beauty = image.rgb(x, y, 0);
      // Each layer and the beauty are means of the same exact sums: only the final rounding
      // to float differs.
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c], beauty[c], 1e-5f * (1.0f + beauty[c])) << x << "," << y;
    }
  for (int k = 0; k < kLightKindCount; ++k) EXPECT_GT(totals[k].average(), 0.0f) << aov_name(light_aov(LightKind(k)));
}

// Direct light only (one bounce), no media, no emitter in view: everything is surface direct.
TEST(FilmScenes, OneBounceOfAPointLightIsAllSurfaceDirect) {
  SceneDesc desc = camera_at({0, 1, 5}, {0, 0.5f, 0}, {12, 8}, 40.0f);
  desc.shapes.push_back({RectangleShape{{-3, 0, 3}, {6, 0, 0}, {0, 0, -6}}, {}, add_material(desc, DiffuseBsdf{})});
  desc.lights.push_back(PointLight{{0, 2, 0}, RGB(5.0f)});
  const auto scene = Scene::build(desc);
  RenderSettings s = settings_for(desc, 4);
  s.path.limits.max_bounces = 1;
  const Image image = render(*scene, s).image;
  double direct = 0.0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      direct += layer(image, x, y, LightKind::kSurfaceDirect).average();
      for (int k = 1; k < kLightKindCount; ++k) EXPECT_EQ(layer(image, x, y, LightKind(k)), RGB(0.0f));
    }
  EXPECT_GT(direct, 0.0);
}

// The case: an opaque wall behind a 2 m fog slab (sigma_s = 1). Alpha is 1 in every
// pixel, and depth and normal are the wall's, although most camera paths scatter before it.
TEST(FilmScenes, AlphaDepthAndNormalOfAWallBehindFog) {
  SceneDesc desc = camera_at({0, 0, 5}, {0, 0, 0}, {8, 8}, 20.0f);
  desc.shapes.push_back({RectangleShape{{-3, -3, -2}, {6, 0, 0}, {0, 6, 0}}, {}, add_material(desc, DiffuseBsdf{})});
  desc.volumes.push_back({BoxVolumeShape{{}, {-3, -3, -1}, {3, 3, 1}}, {RGB(0.0f), RGB(1.0f)}});
  desc.lights.push_back(EnvironmentLight{RGB(1.0f)});
  const auto scene = Scene::build(desc);
  const Image image = render(*scene, settings_for(desc, 16, AovSet::defaults())).image;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      EXPECT_EQ(channel(image, x, y, "A"), 1.0f);
      // Z is the nearest depth of the pixel's samples: the wall plane, 7 m along the axis.
      EXPECT_NEAR(channel(image, x, y, "Z"), 7.0f, 1e-4f);
      EXPECT_NEAR(channel(image, x, y, "N.Z"), 1.0f, 1e-6f);
      EXPECT_NEAR(channel(image, x, y, "albedo.G"), 0.8f, 1e-6f);
    }
}

// Fog alone in front of the background: alpha is 1 - T exactly (no noise), through a slab of
// 2 m seen by an orthographic camera; a holdout medium in front of an emissive wall lets the
// compositor's plate show through it: alpha = T_h and beauty = emission x T_h.
TEST(FilmScenes, AlphaOfFogAloneIsOneMinusTransmittance) {
  SceneDesc desc = camera_at({0, 0, 5}, {0, 0, 0}, {6, 4}, 40.0f);
  desc.camera.projection = CameraProjection::orthographic;
  desc.camera.ortho_width = 1.5f;
  desc.volumes.push_back({BoxVolumeShape{{}, {-2, -2, -1}, {2, 2, 1}}, {RGB(0.1f, 0.2f, 0.3f), RGB(0.5f)}});
  desc.lights.push_back(EnvironmentLight{RGB(1.0f)});
  const auto scene = Scene::build(desc);
  const Image image = render(*scene, settings_for(desc, 8, AovSet::defaults())).image;
  const float t = (std::exp(-2.0f * 0.6f) + std::exp(-2.0f * 0.7f) + std::exp(-2.0f * 0.8f)) / 3.0f;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 6; ++x) EXPECT_NEAR(channel(image, x, y, "A"), 1.0f - t, 1e-5f);
}

TEST(FilmScenes, HoldoutMediumShowsThePlateThroughIt) {
  SceneDesc desc = camera_at({0, 0, 5}, {0, 0, 0}, {6, 4}, 40.0f);
  desc.camera.projection = CameraProjection::orthographic;
  desc.camera.ortho_width = 1.5f;
  const RGB emission(2.0f, 1.0f, 0.5f);
  desc.shapes.push_back(
      {RectangleShape{{-3, -3, -2}, {6, 0, 0}, {0, 6, 0}}, {}, add_material(desc, BlackBsdf{}, emission)});
  VolumePrimitive plate_smoke{BoxVolumeShape{{}, {-2, -2, -1}, {2, 2, 1}}, {}};
  plate_smoke.shader.holdout = 0.4f;
  desc.volumes.push_back(plate_smoke);
  const auto scene = Scene::build(desc);
  const Image image = render(*scene, settings_for(desc, 8, AovSet::defaults())).image;
  const float t = std::exp(-2.0f * 0.4f);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 6; ++x) {
      EXPECT_NEAR(channel(image, x, y, "A"), t, 1e-5f);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(image.at(x, y, c), emission[c] * t, 1e-5f * emission[c]);
    }
}

// A held-out rectangle covering the left half of an orthographic view (its edge on a pixel
// edge) in front of a lit wall, under a visible sky: the held-out pixels are black with
// alpha 0 exactly; the wall's are opaque; a pixel column cut in half by a second holdout's
// edge has alpha 1/2 within its binomial noise.
TEST(FilmScenes, HoldoutAlphaIsItsCoverageAndTheBeautyZero) {
  SceneDesc desc = camera_at({0, 0, 5}, {0, 0, 0}, {16, 8}, 40.0f);
  desc.camera.projection = CameraProjection::orthographic;
  desc.camera.ortho_width = 4.0f;  // 0.25 m per pixel; x from -2 (left) to 2
  const int wall = add_material(desc, DiffuseBsdf{RGB(0.7f)});
  desc.shapes.push_back({RectangleShape{{-3, -3, -1}, {6, 0, 0}, {0, 6, 0}}, {}, wall});
  ShapeDesc left{RectangleShape{{-3, -3, 1}, {3, 0, 0}, {0, 6, 0}}, {}, wall};
  left.holdout = true;
  desc.shapes.push_back(left);
  // Half of pixel column 12 (x in [1, 1.25]): an edge at x = 1.125, in the lower half of rows.
  ShapeDesc sliver{RectangleShape{{1.125f, -3, 1}, {2, 0, 0}, {0, 3, 0}}, {}, wall};
  sliver.holdout = true;
  desc.shapes.push_back(sliver);
  desc.lights.push_back(PointLight{{0, 0, 4}, RGB(10.0f)});
  desc.lights.push_back(EnvironmentLight{RGB(0.5f)});
  const auto scene = Scene::build(desc);
  constexpr int kSpp = 256;
  const Image image = render(*scene, settings_for(desc, kSpp, AovSet::defaults())).image;
  const int a = image.channel_index("A");
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      EXPECT_EQ(image.at(x, y, a), 0.0f);
      EXPECT_EQ(image.rgb(x, y, 0), RGB(0.0f));
    }
  for (int y = 0; y < 4; ++y) {  // upper rows: no sliver
    for (int x = 8; x < 16; ++x) EXPECT_EQ(image.at(x, y, a), 1.0f);
    EXPECT_GT(image.rgb(10, y, 0).average(), 0.0f);
  }
  // Lower rows: column 12 half covered (binomial standard error sqrt(0.25 / spp) = 0.031;
  // 4 of them), columns 13-15 wholly.
  for (int y = 4; y < 8; ++y) {
    EXPECT_NEAR(image.at(12, y, a), 0.5f, 4.0f * std::sqrt(0.25f / kSpp));
    for (int x = 13; x < 16; ++x) EXPECT_EQ(image.at(x, y, a), 0.0f);
  }
}

// The orthographic `slab` built-in: three absorbing boxes 0.5, 1 and 2 m thick under a sky of
// radiance 1, box edges on pixel edges; every pixel is exp(-sigma d) (absorption by weight makes
// it exact, so 0.1 % is float rounding, not noise).
TEST(FilmScenes, OrthographicSlabIsBeerLambert) {
  const SceneDesc desc = parse_builtin(*find_builtin("slab"));
  const auto scene = Scene::build(desc);
  const Image image = render(*scene, settings_for(desc, 4, AovSet::defaults())).image;
  ASSERT_EQ(image.width(), 96);
  ASSERT_EQ(image.height(), 32);
  const Camera camera = scene->camera({96, 32});
  int inside = 0;
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 96; ++x) {
      // The pixel centre's ray (straight down) and the box it crosses: the scene's three boxes,
      // x in [-2.75, -1.25], [-0.75, 0.75], [1.25, 2.75], z in [-0.5, 0.5], 0.5, 1 and 2 m high.
      const Vec3 o = camera.generate_ray({float(x) + 0.5f, float(y) + 0.5f}).origin;
      float d = 0.0f;
      if (std::abs(o.z) < 0.5f)
        d = o.x > -2.75f && o.x < -1.25f ? 0.5f : std::abs(o.x) < 0.75f ? 1.0f : o.x > 1.25f && o.x < 2.75f ? 2.0f : 0.0f;
      inside += d > 0.0f;
      const float expected = std::exp(-d);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(image.at(x, y, c), expected, 1e-3f * expected) << x << "," << y;
      EXPECT_NEAR(channel(image, x, y, "A"), 1.0f - expected, 1e-5f);
    }
  EXPECT_EQ(inside, 3 * 24 * 16);  // box edges on pixel edges
}

// A plane of emissive stripes at the focus distance: every lens sample of a film point meets the
// plane where the pinhole ray does, so the thin-lens image equals the pinhole image (up to
// samples that land within float error of a stripe edge). Focused elsewhere, the stripes blur.
TEST(FilmScenes, ThinLensImageOfTheFocusPlaneEqualsThePinholeImage) {
  SceneDesc desc = camera_at({0, 0, 4}, {0, 0, 0}, {32, 16}, 30.0f);
  const int white = add_material(desc, BlackBsdf{}, RGB(1.0f));
  for (int i = -4; i < 4; i += 2)
    desc.shapes.push_back({RectangleShape{{0.2f * float(i), -2, 0}, {0.2f, 0, 0}, {0, 4, 0}}, {}, white});
  const auto render_with = [&](float aperture, float focus) {
    SceneDesc d = desc;
    d.camera.aperture_radius = aperture;
    d.camera.focus_distance = focus;
    const auto scene = Scene::build(d);
    return render(*scene, settings_for(d, 16, AovSet{})).image;
  };
  const Image pinhole = render_with(0.0f, 0.0f);
  const Image focused = render_with(0.3f, 4.0f);
  const Image blurred = render_with(0.3f, 2.0f);
  double focused_error = 0.0, blurred_error = 0.0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 32; ++x) {
      focused_error += std::abs(focused.at(x, y, 0) - pinhole.at(x, y, 0));
      blurred_error += std::abs(blurred.at(x, y, 0) - pinhole.at(x, y, 0));
    }
  focused_error /= 32 * 16;
  blurred_error /= 32 * 16;
  EXPECT_LT(focused_error, 1e-3);  // one sample in 16 flipping in one pixel of 512 is 1.2e-4
  EXPECT_GT(blurred_error, 0.05);
}

// A frame rendered as three sample ranges into separate films -- one saved to disk and loaded
// back -- and merged equals one render of all the samples, bit for bit (exact film sums).
TEST(FilmScenes, SampleRangesMergedEqualOneRenderBitForBit) {
  const SceneDesc desc = every_kind_of_light();
  const auto scene = Scene::build(desc);
  RenderSettings s = settings_for(desc, 6);
  Film whole(s.resolution, s.aovs);
  render_into(whole, *scene, s);
  Film merged(s.resolution, s.aovs);
  for (const auto& [first, count] : {std::pair{0, 1}, std::pair{1, 3}, std::pair{4, 2}}) {
    RenderSettings part = s;
    part.first_sample = first;
    part.spp = count;
    Film film(s.resolution, s.aovs);
    render_into(film, *scene, part);
    if (first == 1) {
      const std::string path = ::testing::TempDir() + "caligo_range.film";
      film.save(path);
      film = Film::load(path);
    }
    merged.merge(film);
  }
  EXPECT_TRUE(merged == whole);
  EXPECT_TRUE(merged.resolve() == whole.resolve());
}

// A crop window renders only its pixels; they equal the full render's there.
TEST(FilmScenes, CropWindowRendersItsPixelsOnly) {
  const SceneDesc desc = every_kind_of_light();
  const auto scene = Scene::build(desc);
  RenderSettings s = settings_for(desc, 2, AovSet::defaults());
  const Image full = render(*scene, s).image;
  s.crop = {0.25f, 0.5f, 0.5f, 1.0f};
  const Image cropped = render(*scene, s).image;
  const PixelBounds b = s.crop.pixels(s.resolution);
  for (int y = 0; y < full.height(); ++y)
    for (int x = 0; x < full.width(); ++x) {
      const bool inside = x >= b.min.x && x < b.max.x && y >= b.min.y && y < b.max.y;
      for (int c = 0; c < full.channel_count(); ++c) {
        if (inside) {
          EXPECT_EQ(cropped.at(x, y, c), full.at(x, y, c));
        } else if (full.channels()[size_t(c)] != "Z") {
          EXPECT_EQ(cropped.at(x, y, c), 0.0f);
        }
      }
    }
}

}  // namespace
}  // namespace caligo

namespace caligo {
namespace {

// Progressive passes, and a pass stopped part-way (as a signal stops it) then resumed, end bit
// for bit where one render of all the samples does: each pixel continues from its own count.
TEST(FilmScenes, StoppedAndResumedPassesEqualOneRenderBitForBit) {
  const SceneDesc desc = every_kind_of_light();
  const auto scene = Scene::build(desc);
  RenderSettings s = settings_for(desc, 9);
  Film whole(s.resolution, s.aovs);
  render_into(whole, *scene, s);

  Film passes(s.resolution, s.aovs);
  render_up_to(passes, *scene, s, 2);
  render_up_to(passes, *scene, s, 5);
  render_up_to(passes, *scene, s, 9);
  EXPECT_TRUE(passes == whole);

  // Stopped from another thread while the pass runs (at an unknown pixel), then resumed.
  Film stopped(s.resolution, s.aovs);
  std::atomic<bool> stop{false};
  std::thread stopper([&stop] {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    stop = true;
  });
  render_up_to(stopped, *scene, s, 9, &stop);
  stopper.join();
  render_up_to(stopped, *scene, s, 9);
  EXPECT_TRUE(stopped == whole);
}

}  // namespace
}  // namespace caligo

namespace caligo {
namespace {

// Glass is opaque to alpha (as in Arnold, and Cycles without "transparent glass"): a glass sphere
// over a hidden sky has alpha 1 where it covers the pixel (the sky hidden from the camera stays
// hidden through specular chains: EnvironmentLight::visible).
TEST(FilmScenes, GlassIsOpaqueToAlpha) {
  SceneDesc desc = camera_at({0, 0, 5}, {0, 0, 0}, {4, 4}, 5.0f);  // the sphere fills the view
  desc.shapes.push_back({SphereShape{{0, 0, 0}, 1.0f}, {}, add_material(desc, DielectricBsdf{1.5f})});
  EnvironmentLight sky{RGB(1.0f)};
  sky.visible = false;
  desc.lights.push_back(sky);
  const auto scene = Scene::build(desc);
  const Image image = render(*scene, settings_for(desc, 4, AovSet::defaults())).image;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) EXPECT_EQ(channel(image, x, y, "A"), 1.0f);
}

}  // namespace
}  // namespace caligo
