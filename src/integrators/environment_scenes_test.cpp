// Image-based lighting in the path tracer: a constant environment map renders like the
// constant environment light (surface and volume furnaces), a map bright in one pixel block
// lights a sphere from the direction the lat-long convention names (and rotation turns it),
// and visible = false hides the environment from the camera without changing the lighting.
// Standard errors are estimated from the spread of the pixel values, all of which have the
// same expectation in these scenes.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "core/math.h"
#include "lights/environment_map.h"
#include "integrators/test_scenes.h"
#include "render/render.h"

namespace caligo {
namespace {

using testing::camera_at;

int add_material(SceneDesc& desc, Bsdf bsdf) {
  desc.materials.push_back({std::to_string(desc.materials.size()), bsdf, {}, false});
  return int(desc.materials.size()) - 1;
}

Image render_desc(const SceneDesc& desc, int spp, int max_bounces = 8) {
  const auto scene = Scene::build(desc);
  RenderSettings s = render_settings(desc);
  s.spp = spp;
  s.path.limits.max_bounces = max_bounces;
  return render(*scene, s).image;
}

struct PixelStats {
  double mean, standard_error;
};

// Mean of channel g over pixels [x0, x1) x [y0, y1), and its standard error.
PixelStats stats(const Image& image, int x0 = 0, int y0 = 0, int x1 = -1, int y1 = -1) {
  if (x1 < 0) x1 = image.width();
  if (y1 < 0) y1 = image.height();
  double sum = 0.0, sum2 = 0.0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const double v = image.rgb(x, y, 0).g;
      sum += v;
      sum2 += v * v;
    }
  const double n = double(x1 - x0) * (y1 - y0);
  const double mean = sum / n;
  return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n)};
}

EnvironmentLight constant_map_light(float value) {
  EnvironmentLight l{RGB(1.0f)};
  l.map = std::make_shared<const EnvironmentMap>(32, 16, std::vector<RGB>(32 * 16, RGB(value)));
  return l;
}

// A map black but for a 4 x 4 pixel block of radiance 100 centred on (u, v).
std::shared_ptr<const EnvironmentMap> block_map(float u, float v) {
  constexpr int w = 64, h = 32;
  std::vector<RGB> px(w * h, RGB(0.0f));
  const int cx = int(std::lround(u * w)), cy = int(std::lround(v * h));
  for (int y = cy - 2; y < cy + 2; ++y)
    for (int x = cx - 2; x < cx + 2; ++x) px[size_t(y * w + x)] = RGB(100.0f);
  return std::make_shared<const EnvironmentMap>(w, h, std::move(px));
}

// A convex diffuse sphere (albedo 0.5) filling the view under a uniform sky of radiance 2:
// every pixel is 0.5 * 2 = 1, with the constant light and with a constant map alike.
TEST(EnvironmentScenes, ConstantMapMatchesConstantLightOnADiffuseSphere) {
  SceneDesc desc = camera_at({0, 0, 5}, {0, 0, 0}, {16, 16}, 10.0f);  // the sphere covers every pixel
  desc.shapes.push_back({SphereShape{{0, 0, 0}, 1.0f}, {}, add_material(desc, DiffuseBsdf{RGB(0.5f)})});
  desc.lights = {EnvironmentLight{RGB(2.0f)}};
  const PixelStats constant = stats(render_desc(desc, 32));
  desc.lights = {constant_map_light(2.0f)};
  const PixelStats mapped = stats(render_desc(desc, 32));
  std::printf("diffuse sphere: constant light %.4f +- %.4f, constant map %.4f +- %.4f (exact 1)\n", constant.mean,
              constant.standard_error, mapped.mean, mapped.standard_error);
  EXPECT_NEAR(constant.mean, 1.0, 4.0 * constant.standard_error + 1e-4);
  EXPECT_NEAR(mapped.mean, 1.0, 4.0 * mapped.standard_error + 1e-4);
}

// The volume furnace of volume_scenes_test.cpp with a constant map: a non-absorbing medium
// neither gains nor loses light, so every pixel sees the sky's radiance (0.5 here).
TEST(EnvironmentScenes, ConstantMapVolumeFurnace) {
  SceneDesc desc = camera_at({0, 0, 5}, {0, 0, 0}, {12, 12}, 30.0f);
  VolumePrimitive fog{SphereVolumeShape{Sphere::make({0, 0, 0}, 1.5f, {})}, {RGB(0.0f), RGB(1.2f, 1.0f, 0.7f)}};
  fog.shader.phase = HenyeyGreensteinPhase{0.6f};
  desc.volumes.push_back(fog);
  desc.lights = {constant_map_light(0.5f)};
  const PixelStats furnace = stats(render_desc(desc, 128, 1000));
  std::printf("volume furnace with a constant map: %.4f +- %.4f (exact 0.5)\n", furnace.mean, furnace.standard_error);
  EXPECT_NEAR(furnace.mean, 0.5, 4.0 * furnace.standard_error + 1e-4);
}

// The block at u = 0.75, v = 0.25 is the direction (cos 45, sin 45, 0): up and to +X, which the
// camera (on +Z looking at -Z, +Y up) sees as the upper right. A diffuse sphere is brightest
// in its upper-right quadrant; turned by 180 degrees about +Y the light comes from the upper
// left.
TEST(EnvironmentScenes, LatLongConventionLightsFromTheNamedDirection) {
  SceneDesc desc = camera_at({0, 0, 5}, {0, 0, 0}, {16, 16}, 10.0f);
  desc.shapes.push_back({SphereShape{{0, 0, 0}, 1.0f}, {}, add_material(desc, DiffuseBsdf{RGB(0.5f)})});
  EnvironmentLight light{RGB(1.0f)};
  light.map = block_map(0.75f, 0.25f);
  for (float rotation : {0.0f, 180.0f}) {
    light.cos_rotation = std::cos(radians(rotation));
    light.sin_rotation = std::sin(radians(rotation));
    desc.lights = {light};
    const Image image = render_desc(desc, 16, 1);
    // Rows run top to bottom, columns left to right.
    const double upper_left = stats(image, 0, 0, 8, 8).mean, upper_right = stats(image, 8, 0, 16, 8).mean;
    const double lower_left = stats(image, 0, 8, 8, 16).mean, lower_right = stats(image, 8, 8, 16, 16).mean;
    std::printf("rotation %g: quadrants UL %.4f UR %.4f LL %.4f LR %.4f\n", rotation, upper_left, upper_right,
                lower_left, lower_right);
    // The lit quadrant, its two neighbours (lit at grazing angles) and the opposite one.
    const double lit = rotation == 0.0f ? upper_right : upper_left;
    const double beside = rotation == 0.0f ? upper_left : upper_right;
    const double below = rotation == 0.0f ? lower_right : lower_left;
    const double opposite = rotation == 0.0f ? lower_left : lower_right;
    EXPECT_GT(lit, 3.0 * beside);
    EXPECT_GT(lit, 3.0 * below);
    EXPECT_GT(lit, 20.0 * opposite);
  }
}

// visible = false: the camera sees black where it saw the sky, also through glass (a chain of
// specular events), while a diffuse surface's lighting is the same to the bit.
TEST(EnvironmentScenes, InvisibleEnvironmentStillLights) {
  SceneDesc desc = camera_at({0, 0, 5}, {0, 0, 0}, {16, 16}, 10.0f);
  desc.shapes.push_back({SphereShape{{0, 0, 0}, 1.0f}, {}, add_material(desc, DiffuseBsdf{RGB(0.5f)})});
  EnvironmentLight light = constant_map_light(2.0f);
  light.map = block_map(0.6f, 0.4f);  // a non-uniform map, so MIS weights matter
  desc.lights = {light};
  const Image seen = render_desc(desc, 8);
  light.visible = false;
  desc.lights = {light};
  const Image hidden = render_desc(desc, 8);
  EXPECT_TRUE(seen == hidden);  // every pixel is the sphere: lighting only

  SceneDesc sky = camera_at({0, 0, 5}, {0, 0, -10}, {8, 8}, 60.0f);
  sky.lights = {EnvironmentLight{RGB(1.0f)}};
  std::get<EnvironmentLight>(sky.lights[0]).visible = false;
  EXPECT_EQ(stats(render_desc(sky, 4)).mean, 0.0);

  SceneDesc glass = camera_at({0, 0, 5}, {0, 0, 0}, {8, 8}, 10.0f);
  glass.shapes.push_back({SphereShape{{0, 0, 0}, 1.0f}, {}, add_material(glass, DielectricBsdf{1.5f})});
  glass.lights = {EnvironmentLight{RGB(1.0f)}};
  EXPECT_NEAR(stats(render_desc(glass, 64, 100)).mean, 1.0, 0.02);  // invisible glass in a uniform sky
  std::get<EnvironmentLight>(glass.lights[0]).visible = false;
  EXPECT_EQ(stats(render_desc(glass, 16, 100)).mean, 0.0);
}

}  // namespace
}  // namespace caligo
