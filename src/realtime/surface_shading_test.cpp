// Surface shading against closed forms: a diffuse plane under a point light (with and
// without its shadow map, which must not self-shadow the plane), the same in homogeneous
// fog, and one-sided emission.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <random>

#include "realtime/scene_buffers.h"
#include "realtime/shadow_map.h"
#include "lights/gobo.h"
#include "lights/ies.h"
#include "lights/light_profile.h"
#include "realtime/surface_shading.h"
#include "realtime/surface_shading_internal.h"
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
  const std::vector<FrameLight> lights{{*shaded_light(scene.lights()[0]), {}, shadow}};
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
  const auto shadow = render_shadow_map(raster, *shaded_light(scene->lights()[0]), 256, scene->surfaces().bounds());
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

// Shades `desc` with shadow maps for every light, SIMD and scalar, and compares: within 1e-4
// relative at >= 99.9 % of pixels (the two reconstruct p with different rounding, which can
// move a shadow lookup across a texel boundary).
void expect_simd_matches_scalar(const SceneDesc& desc) {
  const auto scene = Scene::build(desc);
  const RasterScene raster = RasterScene::build(*scene);
  const View view = View::from_camera(scene->camera({203, 141}), {203, 141});
  const GBuffer g = rasterize_gbuffer(raster, view);
  std::vector<std::optional<ShadowMap>> maps;
  std::vector<FrameLight> lights;
  for (const Light& l : scene->lights()) maps.push_back(render_shadow_map(raster, *shaded_light(l), 512, raster.bounds()));
  for (size_t i = 0; i < maps.size(); ++i)
    lights.push_back({*shaded_light(scene->lights()[i]), {}, maps[i] ? &*maps[i] : nullptr, i});
  const ColorPlanes simd = shade_surfaces(g, view, *scene, lights, true);
  const ColorPlanes scalar = shade_surfaces(g, view, *scene, lights, false);
  int differ = 0, lit = 0;
  for (size_t i = 0; i < simd.r.data.size(); ++i) {
    lit += scalar.r.data[i] > 0.0f;
    for (const Plane* p : {&simd.r, &simd.g, &simd.b}) {
      const Plane& q = p == &simd.r ? scalar.r : (p == &simd.g ? scalar.g : scalar.b);
      if (!(std::abs(p->data[i] - q.data[i]) <= 1e-4f * std::abs(q.data[i]) + 1e-7f)) {
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
  expect_simd_matches_scalar(desc);
}

std::shared_ptr<const GoboImage> test_gobo() {
  // Saturated colours in cells of different sizes: every bilinear weight matters.
  std::vector<RGB> pixels;
  for (int y = 0; y < 13; ++y)
    for (int x = 0; x < 17; ++x)
      pixels.push_back(
          RGB(float((x * 7 + y * 3) % 5) / 4.0f, float((x + 2 * y) % 3) / 2.0f, (x ^ y) & 1 ? 1.0f : 0.1f));
  return std::make_shared<const GoboImage>(17, 13, std::move(pixels));
}

// Gobo spot and box lights (rotated, offset), IES point and spot lights, and media of every
// kind the SIMD transmittance treats differently: a fog box around everything (the camera
// and light segments lie wholly inside it in most tiles), a rotated homogeneous box, a
// scaled sphere with noise (mean density), a radial-falloff puff (media.h's quadrature lane
// by lane) and a sphere far from everything (skipped per tile).
TEST(SurfaceShading, SimdMatchesScalarWithProfilesAndMedia) {
  SceneDesc desc = test_scenes::box_sphere_quad();
  const auto gobo = test_gobo();
  const auto ies = std::make_shared<const IesProfile>(IesProfile::parse(
      "IESNA:LM-63-2002\nTILT=NONE\n1 1000 1 4 3 1 2 0 0 0\n1.0 1.0 100\n0 20 60 120\n0 45 90\n"
      "100 80 30 0 90 60 40 5 70 70 20 10\n",
      "test.ies"));
  SpotLight spot;
  spot.position = {-0.5f, 3.5f, 1.5f};
  spot.direction = normalize(Vec3{0.2f, -1.0f, -0.4f});
  spot.up = normalize(cross(cross(spot.direction, Vec3{0, 0, 1}), spot.direction));
  spot.cos_outer = std::cos(0.7f);
  spot.cos_inner = std::cos(0.4f);
  spot.intensity = RGB(25.0f, 20.0f, 15.0f);
  spot.range = 12.0f;
  spot.gobo = {gobo, {0.13f, -0.21f}, 0.4f};
  desc.lights.push_back(spot);
  SpotLight ies_spot = spot;
  ies_spot.position = {1.5f, 3.0f, 1.0f};
  ies_spot.direction = normalize(Vec3{-0.3f, -1.0f, -0.1f});
  ies_spot.up = normalize(cross(cross(ies_spot.direction, Vec3{0, 0, 1}), ies_spot.direction));
  ies_spot.gobo = {};
  ies_spot.ies = {ies, ies_spot.direction};
  desc.lights.push_back(ies_spot);
  desc.lights.push_back(PointLight{
      {0.2f, 2.6f, 0.9f}, RGB(5.0f, 4.0f, 3.0f), 8.0f, {ies, normalize(Vec3{0.2f, -1.0f, -0.3f})}});
  BoxLight box;
  box.position = {0.3f, 4.0f, -0.2f};
  box.direction = normalize(Vec3{0.1f, -1.0f, 0.2f});
  box.up = normalize(cross(cross(box.direction, Vec3{0, 0, 1}), box.direction));
  box.half_width = 1.7f;
  box.half_height = 1.2f;
  box.range = 6.0f;
  box.irradiance = RGB(2.0f);
  box.gobo = {gobo, {-0.3f, 0.05f}, -1.1f};
  desc.lights.push_back(box);
  desc.lights.push_back(DirectionalLight{normalize(Vec3{0.5f, -1.0f, 0.3f}), RGB(1.0f, 0.9f, 0.8f)});
  const auto medium = [](float sigma_t) {
    VolumeShader s;
    s.sigma_a = RGB(0.3f, 0.5f, 0.7f) * sigma_t;
    s.sigma_s = RGB(0.7f, 0.5f, 0.3f) * sigma_t;
    return s;
  };
  desc.volumes.push_back({BoxVolumeShape{{}, {-10, -1, -10}, {10, 8, 10}}, medium(0.04f)});
  desc.volumes.push_back(
      {BoxVolumeShape{Transform::translate({-1.0f, 0.5f, 0.5f}) * Transform::rotate(0.7f, {1, 2, 0}),
                      {-0.8f, -0.5f, -0.6f},
                      {0.8f, 0.5f, 0.6f}},
       medium(0.6f)});
  VolumeShader noisy = medium(0.5f);
  noisy.noise = NoiseModulation{2.0f, 0.7f, {}, {}};
  desc.volumes.push_back(
      {SphereVolumeShape{Sphere::make({1.0f, 1.5f, 1.5f}, 0.9f, Transform::scale({1.0f, 0.6f, 1.3f}))},
       noisy});
  VolumeShader puff = medium(1.5f);
  puff.field = RadialFalloffDensity{2.0f};
  desc.volumes.push_back({SphereVolumeShape{Sphere::make({-0.3f, 1.2f, 2.0f}, 0.7f, {})}, puff});
  desc.volumes.push_back({SphereVolumeShape{Sphere::make({40.0f, 2.0f, -40.0f}, 3.0f, {})}, medium(1.0f)});
  expect_simd_matches_scalar(desc);
}

// The buffer-reusing overload writes every pixel: a buffer full of stale values (NaN) ends
// up identical to a fresh frame, sky included.
TEST(SurfaceShading, ReusedBufferIsOverwritten) {
  SceneDesc desc = test_scenes::box_sphere_quad();
  desc.camera.look_at = {0.0f, 2.0f, 0.0f};  // the horizon crosses the frame: sky tiles and groups
  desc.lights.push_back(DirectionalLight{normalize(Vec3{0.5f, -1.0f, 0.3f}), RGB(1.0f, 0.9f, 0.8f)});
  const auto scene = Scene::build(desc);
  const View view = View::from_camera(scene->camera({203, 141}), {203, 141});
  const GBuffer g = rasterize_gbuffer(RasterScene::build(*scene), view);
  const std::vector<FrameLight> lights{{*shaded_light(scene->lights()[0]), {}, nullptr}};
  for (bool simd : {true, false}) {
    const ColorPlanes fresh = shade_surfaces(g, view, *scene, lights, simd);
    ColorPlanes reused(203, 141);
    for (Plane* p : {&reused.r, &reused.g, &reused.b}) std::fill(p->data.begin(), p->data.end(), NAN);
    shade_surfaces(g, view, *scene, lights, reused, simd);
    int sky = 0;
    for (size_t i = 0; i < fresh.r.data.size(); ++i) {
      sky += g.depth.data[i] >= kSkyDepth;
      ASSERT_EQ(reused.r.data[i], fresh.r.data[i]) << i;
      ASSERT_EQ(reused.g.data[i], fresh.g.data[i]) << i;
      ASSERT_EQ(reused.b.data[i], fresh.b.data[i]) << i;
    }
    EXPECT_GT(sky, 203 * 10);
  }
}

// Tile culling of spot lights by their cone must never drop a box in which spot_cone is
// non-zero somewhere: random boxes, brute-force samples of each. It must also cull (boxes
// behind the light and well off the axis), or it would be no culling at all.
TEST(SurfaceShading, SpotConeCullingIsConservative) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  int reached = 0, culled = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    SpotLight l;
    l.position = {u(rng) * 4 - 2, u(rng) * 4 - 2, u(rng) * 4 - 2};
    l.direction = normalize(Vec3{u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f});
    const float outer = 0.05f + 1.45f * u(rng);  // up to 83 degrees
    l.cos_outer = std::cos(outer);
    l.cos_inner = std::cos(outer * 0.5f);
    Bounds3 box;
    const Vec3 c{u(rng) * 12 - 6, u(rng) * 12 - 6, u(rng) * 12 - 6};
    const Vec3 half{0.05f + u(rng), 0.05f + u(rng), 0.05f + u(rng)};
    box.lo = c - half;
    box.hi = c + half;
    bool lit = false;
    constexpr int kN = 9;
    for (int i = 0; i < kN && !lit; ++i)
      for (int j = 0; j < kN && !lit; ++j)
        for (int k = 0; k < kN && !lit; ++k) {
          const Vec3 d = box.hi - box.lo;
          const float s = 1.0f / float(kN - 1);
          const Vec3 p = box.lo + Vec3(d.x * float(i) * s, d.y * float(j) * s, d.z * float(k) * s);
          lit = length(p - l.position) > 0.0f && spot_cone(l, normalize(p - l.position)) > 0.0f;
        }
    const bool may = shading::spot_cone_may_reach(l, box);
    if (lit) {
      ASSERT_TRUE(may) << trial;
    }
    reached += may;
    culled += !may;
  }
  EXPECT_GT(culled, 1000);
  EXPECT_GT(reached, 300);
}

}  // namespace
}  // namespace caligo
