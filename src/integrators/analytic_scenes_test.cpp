// The path tracer against scenes with closed-form answers. Each test states its tolerance;
// sample counts are chosen so the Monte Carlo error sits well inside it.
#include <gtest/gtest.h>

#include <cmath>

#include "render/render.h"

namespace caligo {
namespace {

SceneDesc camera_at(Vec3 position, Vec3 look_at, Vec2i resolution) {
  SceneDesc desc;
  desc.file = "test";
  desc.camera.position = position;
  desc.camera.look_at = look_at;
  desc.camera.resolution = resolution;
  desc.camera.fov_degrees = 60.0f;
  return desc;
}

int add_material(SceneDesc& desc, Bsdf bsdf, RGB emission = {}, bool two_sided = false) {
  desc.materials.push_back({std::to_string(desc.materials.size()), bsdf, emission, two_sided});
  return int(desc.materials.size()) - 1;
}

RGB mean_rgb(const Image& image, bool (*keep)(const Image&, int, int) = nullptr) {
  double r = 0, g = 0, b = 0;
  int n = 0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      if (keep && !keep(image, x, y)) continue;
      const RGB c = image.rgb(x, y, 0);
      r += c.r, g += c.g, b += c.b, ++n;
    }
  return RGB(float(r / n), float(g / n), float(b / n));
}

RenderResult render_desc(const SceneDesc& desc, int spp, int max_bounces) {
  const auto scene = Scene::build(desc);
  RenderSettings settings = render_settings(desc);
  settings.spp = spp;
  settings.path.limits.max_bounces = max_bounces;
  return render(*scene, settings);
}

// A diffuse sphere of radius R and reflectance rho with a point light of intensity I at its
// centre. Every wall point receives E = I / R^2 directly, so the direct radiance is
// rho I / (pi R^2); with all bounces the interior is a furnace: L = rho I / (pi R^2 (1 - rho)).
SceneDesc point_in_sphere(float rho) {
  SceneDesc desc = camera_at({0.3f, 0.2f, 0}, {1, 0.5f, 0.2f}, {16, 16});
  desc.shapes.push_back({SphereShape{{0, 0, 0}, 2.0f}, {}, add_material(desc, DiffuseBsdf{RGB(rho)})});
  desc.lights.push_back(PointLight{{0, 0, 0}, RGB(4.0f)});
  return desc;
}

TEST(AnalyticScenes, PointLightInsideDiffuseSphereDirect) {
  const RGB mean = mean_rgb(render_desc(point_in_sphere(0.5f), 4, 1).image);
  const float expected = 0.5f * 4.0f / (kPi * 4.0f);
  EXPECT_NEAR(mean.g, expected, 0.01f * expected);
}

TEST(AnalyticScenes, PointLightInsideDiffuseSphereAllBounces) {
  const RGB mean = mean_rgb(render_desc(point_in_sphere(0.5f), 256, 1000).image);
  const float expected = 0.5f * 4.0f / (kPi * 4.0f * 0.5f);
  EXPECT_NEAR(mean.g, expected, 0.01f * expected);
}

// A closed sphere whose walls emit E (both ways) and reflect with albedo a: L = E / (1 - a).
TEST(AnalyticScenes, ClosedDiffuseFurnace) {
  for (float albedo : {0.3f, 0.8f}) {
    SceneDesc desc = camera_at({0, 0, 0}, {0, 0, 1}, {16, 16});
    const int m = add_material(desc, DiffuseBsdf{RGB(albedo)}, RGB(1.0f), true);
    desc.shapes.push_back({SphereShape{{0, 0, 0}, 3.0f}, {}, m});
    const RGB mean = mean_rgb(render_desc(desc, 256, 10000).image);
    const float expected = 1.0f / (1.0f - albedo);
    EXPECT_NEAR(mean.r, expected, 0.01f * expected) << "albedo " << albedo;
  }
}

// A convex diffuse object under a uniform environment L never sees itself: its radiance is
// exactly rho L. Exercises environment sampling, BSDF sampling and their MIS weights.
TEST(AnalyticScenes, ConvexDiffuseObjectUnderUniformSky) {
  SceneDesc desc = camera_at({0, 0, -4}, {0, 0, 0}, {24, 24});
  desc.shapes.push_back({SphereShape{{0, 0, 0}, 1.0f}, {}, add_material(desc, DiffuseBsdf{RGB(0.6f)})});
  desc.lights.push_back(EnvironmentLight{RGB(2.0f)});
  const Image image = render_desc(desc, 64, 8).image;
  const RGB on_sphere = mean_rgb(image, [](const Image& im, int x, int y) { return im.at(x, y, 3) == 1.0f; });
  const RGB background =
      mean_rgb(image, [](const Image& im, int x, int y) { return im.at(x, y, 3) == 0.0f; });
  EXPECT_NEAR(on_sphere.g, 1.2f, 0.01f * 1.2f);
  EXPECT_FLOAT_EQ(background.g, 2.0f);
}

// A lossless glass sphere in a uniform environment is invisible: every path escapes sooner
// or later, and the 1/eta^2 of entering cancels the eta^2 of leaving.
TEST(AnalyticScenes, GlassSphereInUniformSkyIsInvisible) {
  SceneDesc desc = camera_at({0, 0, -4}, {0, 0, 0}, {16, 16});
  desc.camera.fov_degrees = 25.0f;
  desc.shapes.push_back({SphereShape{{0, 0, 0}, 1.0f}, {}, add_material(desc, DielectricBsdf{1.5f})});
  desc.lights.push_back(EnvironmentLight{RGB(1.0f)});
  const RGB mean = mean_rgb(render_desc(desc, 256, 1000).image);
  EXPECT_NEAR(mean.b, 1.0f, 0.01f);
}

// Seen through a null surface, a scene looks exactly as without it.
TEST(AnalyticScenes, NullSurfacesAreInvisible) {
  SceneDesc desc = point_in_sphere(0.5f);
  const Image without = render_desc(desc, 4, 1).image;
  desc.shapes.push_back({SphereShape{{0, 0, 0}, 1.0f}, {}, add_material(desc, NullBsdf{})});
  const Image with = render_desc(desc, 4, 1).image;
  const RGB a = mean_rgb(without), b = mean_rgb(with);
  EXPECT_NEAR(a.r, b.r, 1e-4f);
}

TEST(Render, IdenticalForAnyThreadCount) {
  SceneDesc desc = point_in_sphere(0.7f);
  desc.lights.push_back(QuadLight{{-0.5f, 1.5f, -0.5f}, {1, 0, 0}, {0, 0, 1}, RGB(3.0f)});
  const auto scene = Scene::build(desc);
  RenderSettings settings = render_settings(desc);
  settings.spp = 8;
  settings.threads = 1;
  const Image one = render(*scene, settings).image;
  settings.threads = 2;
  settings.tile_size = 5;
  const Image two = render(*scene, settings).image;
  EXPECT_TRUE(one == two);
  settings.seed = 99;
  EXPECT_FALSE(render(*scene, settings).image == one);
}

}  // namespace
}  // namespace caligo
