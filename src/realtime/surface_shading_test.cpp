// Surface shading against closed forms: a diffuse plane under a point light (with and
// without its shadow map, which must not self-shadow the plane), the same in homogeneous
// fog, and one-sided emission.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "realtime/scene_buffers.h"
#include "realtime/shadow_map.h"
#include "realtime/surface_shading.h"
#include "realtime/test_scenes.h"

namespace caligo {
namespace {

constexpr float kAlbedo = 0.5f;
const Vec3 kLight{0.3f, 2.0f, -0.2f};
const RGB kIntensity{10.0f, 5.0f, 2.0f};

SceneDesc lit_plane() {
  SceneDesc desc;
  desc.file = "test";
  desc.camera.position = {0.0f, 3.0f, 4.0f};
  desc.camera.look_at = {0.0f, 0.0f, 0.0f};
  desc.camera.fov_degrees = 50.0f;
  const int m = test_scenes::add_diffuse(desc, kAlbedo);
  desc.shapes.push_back({RectangleShape{{-20, 0, 20}, {40, 0, 0}, {0, 0, -40}}, {}, m});
  desc.lights.push_back(PointLight{kLight, kIntensity});
  return desc;
}

// albedo / pi * I cos / d^2 on the plane y = 0 (cos = light height / d), times e^(-sigma
// (camera distance + light distance)) in a fog of extinction sigma.
RGB analytic(Vec3 p, Vec3 eye, float sigma) {
  const float d = length(kLight - p);
  const float cos_theta = kLight.y / d;
  const float tr = std::exp(-sigma * (d + length(p - eye)));
  return kIntensity * (kAlbedo * kInvPi * cos_theta / (d * d) * tr);
}

void expect_analytic(const Scene& scene, const GBuffer& g, const View& view, const ShadowMap* shadow,
                     float sigma) {
  const std::vector<FrameLight> lights{{scene.lights()[0], {}, shadow}};
  const ColorPlanes c = shade_surfaces(g, view, scene, lights);
  int checked = 0;
  for (int y = 0; y < view.resolution.y; y += 3)
    for (int x = 0; x < view.resolution.x; x += 3) {
      if (g.depth.at(x, y) >= kSkyDepth) {
        EXPECT_EQ(c.r.at(x, y), 0.0f);  // sky is black
        continue;
      }
      const Vec3 p = view.unproject({float(x) + 0.5f, float(y) + 0.5f}, g.depth.at(x, y));
      const RGB e = analytic(p, view.eye, sigma);
      ASSERT_NEAR(c.r.at(x, y), e.r, 2e-3f * e.r) << x << "," << y;
      ASSERT_NEAR(c.b.at(x, y), e.b, 2e-3f * e.b) << x << "," << y;
      ++checked;
    }
  EXPECT_GT(checked, 100);
}

TEST(SurfaceShading, DiffusePlaneUnderPointLight) {
  const auto scene = Scene::build(lit_plane());
  const RasterScene raster = RasterScene::build(*scene);
  const View view = View::from_camera(scene->camera({96, 72}), {96, 72});
  const auto shadow = render_shadow_map(raster, scene->lights()[0], 256, scene->surfaces().bounds());
  ASSERT_TRUE(shadow);
  for (const GBuffer& g : {rasterize_gbuffer(raster, view), trace_gbuffer(*scene, view)}) {
    expect_analytic(*scene, g, view, nullptr, 0.0f);
    expect_analytic(*scene, g, view, &*shadow, 0.0f);  // no acne: every plane pixel is lit
  }
}

TEST(SurfaceShading, DiffusePlaneInHomogeneousFog) {
  SceneDesc desc = lit_plane();
  const float sigma = 0.15f;
  VolumePrimitive fog;
  fog.shape = BoxVolumeShape{{}, {-30, -1, -30}, {30, 10, 30}};
  fog.shader.sigma_a = RGB(sigma);
  fog.shader.sigma_s = RGB(0.0f);
  desc.volumes.push_back(fog);
  const auto scene = Scene::build(desc);
  const View view = View::from_camera(scene->camera({64, 48}), {64, 48});
  expect_analytic(*scene, rasterize_gbuffer(RasterScene::build(*scene), view), view, nullptr, sigma);
}

// A one-sided emitter glows only towards its front.
TEST(SurfaceShading, OneSidedEmission) {
  for (bool facing : {true, false}) {
    SceneDesc desc;
    desc.file = "test";
    desc.camera.position = {0, 0, 3};
    desc.camera.look_at = {0, 0, 0};
    desc.materials.push_back({"glow", BlackBsdf{}, RGB(2.0f, 1.0f, 0.5f), false});
    const Vec3 e1{2, 0, 0}, e2{0, 2, 0};
    desc.shapes.push_back(
        {facing ? RectangleShape{{-1, -1, 0}, e1, e2} : RectangleShape{{-1, -1, 0}, e2, e1}, {}, 0});
    const auto scene = Scene::build(desc);
    const View view = View::from_camera(scene->camera({32, 32}), {32, 32});
    const GBuffer g = rasterize_gbuffer(RasterScene::build(*scene), view);
    const ColorPlanes c = shade_surfaces(g, view, *scene, {});
    ASSERT_LT(g.depth.at(16, 16), kSkyDepth);
    EXPECT_EQ(c.r.at(16, 16), facing ? 2.0f : 0.0f);
    EXPECT_EQ(c.b.at(16, 16), facing ? 0.5f : 0.0f);
  }
}

// The 8-wide path against the scalar one with every SIMD light type, shadowed, in fog:
// within 1e-4 relative at >= 99.9 % of pixels (the two reconstruct p with different
// rounding, which can move a shadow lookup across a texel boundary).
TEST(SurfaceShading, SimdMatchesScalar) {
  SceneDesc desc = test_scenes::box_sphere_quad();
  desc.lights.push_back(PointLight{{0.2f, 2.6f, 0.9f}, RGB(5.0f, 4.0f, 3.0f), 6.0f});
  SpotLight spot;
  spot.position = {0.3f, 4.0f, 0.5f};
  spot.direction = normalize(Vec3{-0.1f, -1.0f, -0.15f});
  spot.up = normalize(cross(cross(spot.direction, Vec3{0, 0, 1}), spot.direction));
  spot.cos_outer = std::cos(0.8f);
  spot.cos_inner = std::cos(0.6f);
  spot.intensity = RGB(20.0f);
  desc.lights.push_back(spot);
  BoxLight box;
  box.position = {0.0f, 4.0f, 0.0f};
  box.direction = {0, -1, 0};
  box.up = {0, 0, 1};
  box.half_width = 1.5f;
  box.half_height = 1.0f;
  box.range = 6.0f;
  box.irradiance = RGB(2.0f);
  desc.lights.push_back(box);
  desc.lights.push_back(DirectionalLight{normalize(Vec3{0.5f, -1.0f, 0.3f}), RGB(1.0f, 0.9f, 0.8f)});
  VolumePrimitive fog;
  fog.shape = BoxVolumeShape{{}, {-5, -1, -5}, {5, 5, 8}};
  fog.shader.sigma_a = RGB(0.05f);
  fog.shader.sigma_s = RGB(0.02f);
  desc.volumes.push_back(fog);
  const auto scene = Scene::build(desc);
  const RasterScene raster = RasterScene::build(*scene);
  const View view = View::from_camera(scene->camera({203, 141}), {203, 141});
  const GBuffer g = rasterize_gbuffer(raster, view);
  std::vector<std::optional<ShadowMap>> maps;
  std::vector<FrameLight> lights;
  for (const Light& l : scene->lights()) maps.push_back(render_shadow_map(raster, l, 512, raster.bounds()));
  for (size_t i = 0; i < maps.size(); ++i)
    lights.push_back({scene->lights()[i], {}, maps[i] ? &*maps[i] : nullptr});
  const ColorPlanes simd = shade_surfaces(g, view, *scene, lights, true);
  const ColorPlanes scalar = shade_surfaces(g, view, *scene, lights, false);
  int differ = 0, lit = 0;
  for (size_t i = 0; i < simd.r.data.size(); ++i) {
    lit += scalar.r.data[i] > 0.0f;
    for (const Plane* p : {&simd.r, &simd.g, &simd.b}) {
      const Plane& q = p == &simd.r ? scalar.r : (p == &simd.g ? scalar.g : scalar.b);
      if (std::abs(p->data[i] - q.data[i]) > 1e-4f * std::abs(q.data[i]) + 1e-7f) {
        ++differ;
        break;
      }
    }
  }
  EXPECT_GT(lit, int(simd.r.data.size() / 3));
  std::printf("shading SIMD vs scalar: %d of %zu pixels differ by more than 1e-4\n", differ,
              simd.r.data.size());
  EXPECT_LE(differ, int(simd.r.data.size() / 1000)) << differ << " pixels differ";
}

}  // namespace
}  // namespace caligo
