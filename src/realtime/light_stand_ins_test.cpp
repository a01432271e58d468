// The real-time stand-ins of area lights and the environment (light_stand_ins.h): the power
// and the far-field profile of each area light, the median cut's energy and directions, and a
// stand-in's shadow map leaving out its own emitter.
#include "realtime/light_stand_ins.h"

#include <gtest/gtest.h>

#include <cmath>

#include "lights/environment_map.h"
#include "lights/light_profile.h"
#include "realtime/frame_light.h"
#include "realtime/scene_buffers.h"
#include "realtime/shadow_map.h"
#include "realtime/test_scenes.h"
#include "scene/scene.h"

namespace caligo {
namespace {

// Emitted watts agree: the sphere's exactly (float rounding), the flat ones' up to the cosine
// table's linear interpolation (measured < 2e-5 relative; held to 1e-4).
TEST(LightStandIns, AreaLightsKeepTheirPower) {
  const SphereLight sphere{{0, 3, 0}, 0.2f, RGB(5.0f)};
  EXPECT_NEAR(power(Light(stand_in(sphere))), power(Light(sphere)), 1e-6f * power(Light(sphere)));
  const QuadLight quad{{0, 3, 0}, {1, 0, 0}, {0, 0, 0.5f}, RGB(2.0f), false};
  EXPECT_NEAR(power(Light(stand_in(quad))), power(Light(quad)), 1e-4f * power(Light(quad)));
  QuadLight two = quad;
  two.two_sided = true;
  EXPECT_NEAR(power(Light(stand_in(two))), power(Light(two)), 1e-4f * power(Light(two)));
  const TriangleLight tri{{0, 3, 0}, {1, 3, 0}, {0, 3, 1}, RGB(3.0f), false};
  EXPECT_NEAR(power(Light(stand_in(tri))), power(Light(tri)), 1e-4f * power(Light(tri)));
  DiskLight disk;
  disk.center = {0, 2, 0};
  disk.normal = {0, -1, 0};
  disk.radius = 0.4f;
  disk.radiance = RGB(7.0f);
  EXPECT_NEAR(power(Light(stand_in(disk))), power(Light(disk)), 1e-4f * power(Light(disk)));
}

// A flat emitter's intensity is L A cos(theta) about its normal, nothing behind it (one-sided).
TEST(LightStandIns, FlatEmittersFollowTheCosineLaw) {
  const QuadLight quad{{-0.5f, 3, -0.25f}, {1, 0, 0}, {0, 0, 0.5f}, RGB(2.0f), false};  // normal -y
  const PointLight p = stand_in(quad);
  EXPECT_NEAR(p.position.y, 3.0f, 1e-6f);
  EXPECT_NEAR(p.intensity.r, 2.0f * 0.5f, 1e-6f);
  for (float deg : {0.0f, 30.0f, 60.0f, 89.0f}) {
    const float t = radians(deg);
    const Vec3 w{std::sin(t), -std::cos(t), 0.0f};
    EXPECT_NEAR(ies_factor(p.ies, w), std::cos(t), 4e-5f) << deg;
  }
  EXPECT_EQ(ies_factor(p.ies, {0.0f, 1.0f, 0.0f}), 0.0f);
  QuadLight two = quad;
  two.two_sided = true;
  EXPECT_NEAR(ies_factor(stand_in(two).ies, normalize(Vec3{0.3f, 1.0f, 0.0f})), 1.0f / std::sqrt(1.09f), 4e-5f);
}

// The suns of a constant sky carry its whole integral, 4 pi L, in parts equal to within the
// grid's row and column steps (measured 0, 1.4 and 3.9 % apart for 2, 16 and 64 suns; held
// to 5 %); with the horizon cut first and the irradiance E |m|, an upward surface receives
// pi L (measured 1.2e-4 high, from the cells' centre directions; held to 3e-4).
TEST(LightStandIns, MedianCutOfAConstantSky) {
  const EnvironmentLight sky{RGB(0.5f, 1.0f, 2.0f)};
  for (int count : {2, 16, 64}) {
    const std::vector<EnvironmentSun> suns = environment_stand_ins(sky, count);
    ASSERT_EQ(suns.size(), size_t(count));
    RGB sum(0.0f);
    float up = 0.0f, worst = 0.0f;
    for (const EnvironmentSun& s : suns) {
      const RGB e = s.light.irradiance * s.volumetric_scale;
      sum += e;
      EXPECT_NEAR(length(s.light.direction), 1.0f, 1e-5f);
      EXPECT_GE(s.volumetric_scale, 1.0f);
      worst = std::max(worst, std::abs(e.g / (4.0f * kPi / float(count)) - 1.0f));
      up += s.light.irradiance.g * std::max(0.0f, -s.light.direction.y);
    }
    std::printf("%d suns: parts within %.2f %% of equal, upward surface %.6f pi L\n", count, worst * 100.0f, up / kPi);
    EXPECT_LT(worst, 0.05f) << count;
    EXPECT_NEAR(sum.r, 4.0f * kPi * 0.5f, 1e-4f * sum.r) << count;
    EXPECT_NEAR(sum.b, 4.0f * kPi * 2.0f, 1e-4f * sum.b) << count;
    EXPECT_NEAR(up, kPi, 3e-4f * kPi) << count;
  }
}

// A map that is dark but for one bright cell puts a sun on that cell's direction with its
// energy; the integral over every sun is the map's (turned by the light's rotation).
TEST(LightStandIns, MedianCutFindsTheSunOfAMap) {
  constexpr int w = 32, h = 16;
  std::vector<RGB> pixels(size_t(w * h), RGB(0.01f));
  pixels[size_t(5 * w + 20)] = RGB(1000.0f);
  EnvironmentLight light{RGB(2.0f)};
  light.map = std::make_shared<const EnvironmentMap>(w, h, pixels);
  light.cos_rotation = std::cos(0.7f);
  light.sin_rotation = std::sin(0.7f);
  const std::vector<EnvironmentSun> suns = environment_stand_ins(light, 8);
  ASSERT_EQ(suns.size(), 8u);
  RGB sum(0.0f);
  const DirectionalLight* brightest = &suns[0].light;
  for (const EnvironmentSun& s : suns) {
    sum += s.light.irradiance * s.volumetric_scale;
    if (s.light.irradiance.r > brightest->irradiance.r) brightest = &s.light;
  }
  EXPECT_NEAR(sum.r, 2.0f * light.map->integral().r, 1e-4f * sum.r);
  const Vec3 m = latlong_to_direction({20.5f / w, 5.5f / h});
  const Vec3 cell{light.cos_rotation * m.x + light.sin_rotation * m.z, m.y,
                  -light.sin_rotation * m.x + light.cos_rotation * m.z};
  EXPECT_GT(dot(-brightest->direction, cell), std::cos(radians(3.0f)));
}

// A sphere light's stand-in sits inside the sphere's own visible surface: its shadow map must
// leave it out, or nothing would be lit.
TEST(LightStandIns, ShadowMapLeavesOutTheEmittersOwnSurface) {
  SceneDesc desc;
  const int m = test_scenes::add_diffuse(desc, 0.5f);
  desc.shapes.push_back({RectangleShape{{-4, 0, 4}, {8, 0, 0}, {0, 0, -8}}, {}, m});
  desc.lights.push_back(SphereLight{{0, 2, 0}, 0.3f, RGB(1.0f)});
  const auto scene = Scene::build(desc);
  const RasterScene raster = RasterScene::build(*scene);
  const std::vector<FrameLight> lights = frame_lights(desc, desc.lights, 16);
  ASSERT_EQ(lights.size(), 1u);
  EXPECT_EQ(lights[0].skip_emitter, 0);
  const Bounds3 bounds = scene->surfaces().bounds();
  const auto own = render_shadow_map(raster, lights[0].light, 128, bounds, lights[0].skip_emitter);
  const auto blocked = render_shadow_map(raster, lights[0].light, 128, bounds);
  ASSERT_TRUE(own && blocked);
  const Vec3 on_floor{1.0f, 0.01f, 0.5f};
  EXPECT_EQ(own->visibility(on_floor), 1.0f);
  EXPECT_EQ(blocked->visibility(on_floor), 0.0f);
}

// Every environment sun gets its own cache index past the scene's lights, and reports to the
// environment's scene index.
TEST(LightStandIns, EnvironmentSunsHaveTheirOwnCacheIndex) {
  SceneDesc desc;
  desc.lights = {PointLight{{0, 2, 0}, RGB(1.0f)}, EnvironmentLight{RGB(1.0f)}, PointLight{{1, 2, 0}, RGB(1.0f)}};
  const std::vector<FrameLight> lights = frame_lights(desc, desc.lights, 4);
  ASSERT_EQ(lights.size(), 6u);
  const size_t index[] = {0, 1, 3, 4, 5, 2}, scene[] = {0, 1, 1, 1, 1, 2};
  for (size_t i = 0; i < lights.size(); ++i) {
    EXPECT_EQ(lights[i].index, index[i]) << i;
    EXPECT_EQ(lights[i].scene_light, scene[i]) << i;
  }
}

}  // namespace
}  // namespace caligo
