// Partly transparent surfaces (materials/opacity_map.h) as layers of the march record: a card of
// opacity 1/2 in absorbing fog against the analytic transmittance and alpha, a card's shadow, an
// opacity image on a card, and production against the reference ladder (which meets cards by
// chance rather than as layers) in scattering fog with a lamp.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "integrators/ladder_agreement.h"
#include "integrators/test_scenes.h"
#include "render/render.h"

namespace caligo {
namespace {

using testing::camera_at;

int add_material(SceneDesc& desc, Bsdf bsdf, float opacity = 1.0f,
                 std::shared_ptr<const OpacityMap> map = nullptr) {
  Material m{std::to_string(desc.materials.size()), bsdf, RGB(0.0f), false};
  m.opacity = opacity;
  m.opacity_map = std::move(map);
  desc.materials.push_back(m);
  return int(desc.materials.size()) - 1;
}

RenderSettings settings_for(const SceneDesc& desc, int spp) {
  RenderSettings s = render_settings(desc);
  s.spp = spp;
  s.aovs = AovSet::defaults();
  return s;
}

float alpha(const Image& image, int x, int y) { return image.at(x, y, image.channel_index("A")); }

// An orthographic view along -z through 2 m of absorbing fog (sigma_a 0.4) with a black card of
// opacity `card_opacity` across the middle of it, against a white sky.
SceneDesc card_in_fog(float card_opacity, std::shared_ptr<const OpacityMap> map = nullptr) {
  SceneDesc desc = camera_at({0, 0, 5}, {0, 0, 0}, {8, 4}, 40.0f);
  desc.camera.projection = CameraProjection::orthographic;
  desc.camera.ortho_width = 2.0f;  // x from -1 to 1, 0.25 m per pixel
  desc.volumes.push_back({BoxVolumeShape{{}, {-2, -2, -1}, {2, 2, 1}}, {RGB(0.4f), RGB(0.0f)}});
  const int card = add_material(desc, DiffuseBsdf{RGB(0.0f)}, card_opacity, std::move(map));
  desc.shapes.push_back({RectangleShape{{-1, -1, 0}, {2, 0, 0}, {0, 2, 0}}, {}, card});
  desc.lights.push_back(EnvironmentLight{RGB(1.0f)});
  return desc;
}

// Alpha is exact (the record's transmittance, no sampling): 1 - (1/2) e^{-0.8}. The beauty is the
// sky through both, e^{-0.8} / 2, met by paths that choose to pass the card (the others meet the
// black card): its mean within 4 standard errors of the Bernoulli weight.
TEST(OpacityScenes, ACardInAbsorbingFogPassesItsTransparencyAndAlphaIsExact) {
  const SceneDesc desc = card_in_fog(0.5f);
  const auto scene = Scene::build(desc);
  const int spp = 256;
  const Image image = render(*scene, settings_for(desc, spp)).image;
  const float t = 0.5f * std::exp(-0.8f);
  // Per sample the beauty is 0 or t (H + P) / P with P = t, H = 1/2 e^{-0.4} (the card's mass).
  const float h = 0.5f * std::exp(-0.4f), p = t;
  const float big = t * (h + p) / p, q = p / (h + p);
  const double sigma = big * std::sqrt(double(q) * (1 - q));
  const double se = sigma / std::sqrt(double(spp) * 32);
  double mean = 0;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x) {
      EXPECT_NEAR(alpha(image, x, y), 1.0f - t, 1e-5f);
      mean += image.at(x, y, 0) / 32.0;
    }
  std::printf("  card in fog: beauty %.5f expected %.5f (se %.5f)\n", mean, double(t), se);
  EXPECT_NEAR(mean, t, 4.0 * se);
}

// An opacity image (left half 0, right half 1) on the card: the left pixels see the fog's
// transmittance e^{-0.8} exactly, the right ones the black card (alpha 1, beauty 0).
TEST(OpacityScenes, AnOpacityImageCutsTheCard) {
  // Texel centres at u = 1/8, 3/8, 5/8, 7/8: pixels 1 and 2 (u in [1/8, 3/8]) read 0 exactly,
  // pixels 5 and 6 (u in [5/8, 7/8]) read 1; the others blend across the edges.
  auto map = std::make_shared<const OpacityMap>(4, 1, std::vector<float>{0.0f, 0.0f, 1.0f, 1.0f});
  const SceneDesc desc = card_in_fog(1.0f, map);
  const auto scene = Scene::build(desc);
  const Image image = render(*scene, settings_for(desc, 16)).image;
  const float t = std::exp(-0.8f);
  for (int y = 0; y < 4; ++y)
    for (int k = 0; k < 2; ++k) {
      EXPECT_NEAR(alpha(image, 1 + k, y), 1.0f - t, 1e-5f);
      EXPECT_NEAR(image.at(1 + k, y, 0), t, 1e-5f);
      EXPECT_NEAR(alpha(image, 5 + k, y), 1.0f, 1e-6f);
      EXPECT_NEAR(image.at(5 + k, y, 0), 0.0f, 1e-6f);
    }
}

// Direct light from a point lamp on a floor through a card of opacity 0.3 above it: the shadow ray
// passes 0.7 of it, sample for sample (the same sampler), against the scene without the card.
TEST(OpacityScenes, AShadowThroughACardKeepsItsTransparency) {
  const auto floor_scene = [](bool with_card) {
    SceneDesc desc = camera_at({0, 0.8f, 3}, {0, 0, 1.5f}, {8, 6}, 30.0f);  // below the card, seeing only floor
    desc.render.path.limits.max_bounces = 1;
    const int grey = add_material(desc, DiffuseBsdf{RGB(0.5f)});
    desc.shapes.push_back({RectangleShape{{-5, 0, 5}, {10, 0, 0}, {0, 0, -10}}, {}, grey});
    if (with_card)
      desc.shapes.push_back(
          {RectangleShape{{-4, 1, 4}, {8, 0, 0}, {0, 0, -8}}, {}, add_material(desc, DiffuseBsdf{RGB(0.8f)}, 0.3f)});
    desc.lights.push_back(PointLight{{0, 2, 0}, RGB(5.0f)});
    return desc;
  };
  const SceneDesc open = floor_scene(false), carded = floor_scene(true);
  const Image a = render(*Scene::build(open), settings_for(open, 4)).image;
  const Image b = render(*Scene::build(carded), settings_for(carded, 4)).image;
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 8; ++x) {
      ASSERT_GT(a.at(x, y, 0), 0.0f) << x << "," << y;
      EXPECT_NEAR(b.at(x, y, 0), 0.7f * a.at(x, y, 0), 1e-5f * a.at(x, y, 0)) << x << "," << y;
    }
}

// Scattering fog lit by a lamp, a diffuse card of opacity 1/2 between them and a wall behind:
// light reaches the camera around, through and off the card, by single and multiple scattering.
// The image means of production and of the ladder agree (testing::expect_agree's tolerances).
TEST(OpacityScenes, ACardInLitFogAgreesWithTheLadder) {
  SceneDesc desc = camera_at({0, 1, 4}, {0, 1, 0}, {16, 12}, 45.0f);
  desc.volumes.push_back({BoxVolumeShape{{}, {-2, 0, -1.5f}, {2, 2.5f, 2}}, {RGB(0.05f), RGB(0.3f, 0.4f, 0.5f)}});
  const int wall = add_material(desc, DiffuseBsdf{RGB(0.6f)});
  desc.shapes.push_back({RectangleShape{{-3, -0.5f, -1.5f}, {6, 0, 0}, {0, 4, 0}}, {}, wall});
  const int card = add_material(desc, DiffuseBsdf{RGB(0.7f, 0.5f, 0.3f)}, 0.5f);
  desc.shapes.push_back({RectangleShape{{-0.6f, 0.4f, 0.5f}, {1.2f, 0, 0}, {0, 1.2f, 0}}, {}, card});
  // Above the fog: a lamp inside it makes both estimators' tails heavy (1/r^2 at the lamp).
  desc.lights.push_back(PointLight{{0.3f, 3.0f, -0.6f}, RGB(8.0f)});
  // Measured 2026-12: 0.26 combined standard errors (0.36 with the card opaque).
  testing::expect_agree(*Scene::build(desc), 4096, 16384, {}, "card in lit fog");
}

}  // namespace
}  // namespace caligo
