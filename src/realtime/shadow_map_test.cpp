// Shadow-map visibility against Embree occlusion on random points, per light type, and the
// SIMD lookup against the scalar one.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "lights/light_profile.h"
#include "realtime/scene_buffers.h"
#include "realtime/shadow_map.h"
#include "realtime/shadow_map_simd.h"
#include "realtime/test_scenes.h"
#include "scene/scene.h"

namespace caligo {
namespace {

struct Fixture {
  std::unique_ptr<Scene> scene = Scene::build(test_scenes::box_sphere_quad());
  RasterScene raster = RasterScene::build(*scene);
  Bounds3 bounds = scene->surfaces().bounds();
};

// Where a shadow ray from p towards the light ends; nullopt where the light does not reach p.
std::optional<Vec3> light_point(const Light& light, Vec3 p) {
  if (const auto* s = std::get_if<SpotLight>(&light)) {
    if (!delta_arrival(*s, p)) return std::nullopt;
    return s->position;
  }
  if (const auto* pt = std::get_if<PointLight>(&light)) return pt->position;
  if (const auto* b = std::get_if<BoxLight>(&light)) {
    const auto a = delta_arrival(*b, p);
    if (!a) return std::nullopt;
    return p + a->wi * a->distance;
  }
  const auto& d = std::get<DirectionalLight>(light);
  return p - d.direction * 100.0f;
}

struct Counts {
  int points = 0, agree = 0, simd_mismatch = 0, filtered_mismatch = 0;
};

// Uniform points in the scene's box above the floor (some inside the box and sphere).
Counts compare_with_embree(const Fixture& f, const Light& light, int size) {
  const auto map = render_shadow_map(f.raster, *shaded_light(light), size, f.bounds);
  EXPECT_TRUE(map.has_value());
  Counts c;
  if (!map) return c;
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> ux(-3.0f, 3.0f), uy(0.01f, 2.5f), uz(-3.0f, 3.0f);
  std::vector<Vec3> points;
  while (c.points < 4000) {
    const Vec3 p{ux(rng), uy(rng), uz(rng)};
    const auto target = light_point(light, p);
    if (!target) continue;
    ++c.points;
    points.push_back(p);
    const float dist = length(*target - p);
    const Ray ray{p, (*target - p) / dist, 0.0f, dist * (1.0f - 1e-5f)};
    const bool lit = !f.scene->surfaces().occluded(ray);
    if (lit == (map->visibility(p) == 1.0f)) ++c.agree;
  }
  using B = xsimd::batch<float>;
  for (size_t i = 0; i + B::size <= points.size(); i += B::size) {
    alignas(32) float x[B::size], y[B::size], z[B::size], v[B::size];
    for (size_t k = 0; k < B::size; ++k)
      x[k] = points[i + k].x, y[k] = points[i + k].y, z[k] = points[i + k].z;
    shadow_visibility(*map, B::load_aligned(x), B::load_aligned(y), B::load_aligned(z)).store_aligned(v);
    for (size_t k = 0; k < B::size; ++k) c.simd_mismatch += v[k] != map->visibility(points[i + k]);
    surface_shadow_visibility(*map, B::load_aligned(x), B::load_aligned(y), B::load_aligned(z)).store_aligned(v);
    for (size_t k = 0; k < B::size; ++k)
      c.filtered_mismatch += std::abs(v[k] - map->surface_visibility(points[i + k])) > 1e-3f;
  }
  return c;
}

// Disagreement comes from points within the depth slack (1.5 texels) behind a lit surface
// and from shadow edges quantised to texels; >= 98 % agreement is required, and the SIMD
// lookup may differ from the scalar one at <= 0.1 % of points (texel-boundary rounding); so may
// the filtered one by more than 1e-3 (measured: at none; smaller differences are the bilinear
// weights' rounding).
void expect_agreement(const Light& light, const char* name) {
  const Fixture f;
  const Counts c = compare_with_embree(f, light, 512);
  std::printf("%s: shadow map agrees with Embree at %d of %d points; SIMD lookup differs at %d, filtered at %d\n",
              name, c.agree, c.points, c.simd_mismatch, c.filtered_mismatch);
  EXPECT_GE(double(c.agree) / c.points, 0.98) << name << ": " << c.agree << " / " << c.points;
  EXPECT_LE(c.simd_mismatch, c.points / 1000) << name;
  EXPECT_LE(c.filtered_mismatch, c.points / 1000) << name;
}

TEST(ShadowMap, SpotAgreesWithEmbree) {
  SpotLight l;
  l.position = {0.3f, 4.0f, 0.5f};
  l.direction = normalize(Vec3{-0.1f, -1.0f, -0.15f});
  l.up = normalize(cross(cross(l.direction, Vec3{0, 0, 1}), l.direction));
  l.cos_outer = std::cos(0.8f);
  l.cos_inner = std::cos(0.6f);
  l.intensity = RGB(1.0f);
  expect_agreement(l, "spot");
}

TEST(ShadowMap, PointCubeAgreesWithEmbree) {
  expect_agreement(PointLight{{0.2f, 2.6f, 0.9f}, RGB(1.0f)}, "point");
}

TEST(ShadowMap, BoxAgreesWithEmbree) {
  BoxLight l;
  l.position = {0.0f, 4.0f, 0.0f};
  l.direction = normalize(Vec3{0.2f, -1.0f, 0.1f});
  l.up = normalize(cross(Vec3{1, 0, 0}, l.direction));
  l.half_width = 3.0f;
  l.half_height = 2.5f;
  l.range = 6.0f;
  l.irradiance = RGB(1.0f);
  expect_agreement(l, "box");
}

TEST(ShadowMap, DirectionalAgreesWithEmbree) {
  DirectionalLight l;
  l.direction = normalize(Vec3{0.5f, -1.0f, 0.3f});
  l.irradiance = RGB(1.0f);
  expect_agreement(l, "directional");
}

// The surfaces' bilinear PCF ramps across a diagonal shadow edge over about a texel, without
// steps: along a line crossing it in twentieths of a texel, visibility changes by at most
// sqrt(2) / 20 per step (the bilinear weights' slope), where the single tap jumps 0 -> 1; it
// is 0 and 1 more than 1.5 texels from the edge, and crosses 1/2 within a texel of it.
TEST(ShadowMap, SurfaceFilterRampsAcrossAnEdge) {
  SceneDesc desc;
  const int m = test_scenes::add_diffuse(desc, 0.5f);
  desc.shapes.push_back({RectangleShape{{-4, 0, 4}, {8, 0, 0}, {0, 0, -8}}, {}, m});
  const Transform turn = Transform::rotate(0.52f, {0, 1, 0});
  desc.shapes.push_back({RectangleShape{{-2, 1, -2}, {4, 0, 0}, {0, 0, 2}}, turn, m});  // local z in [-2, 0]
  const auto scene = Scene::build(desc);
  const RasterScene raster = RasterScene::build(*scene);
  DirectionalLight sun;
  sun.direction = {0, -1, 0};
  sun.irradiance = RGB(1.0f);
  const auto map = render_shadow_map(raster, sun, 64, scene->surfaces().bounds());
  ASSERT_TRUE(map);
  const Vec3 along = turn.vector({0, 0, 1});  // across the edge, towards the lit side
  Vec3 on_edge = turn.point({0.3f, 0, 0});
  on_edge.y = 0.0f;  // on the floor
  const float texel = map->texel_size(on_edge);
  float prev_filtered = -1.0f, prev_tap = -1.0f, max_step = 0.0f, max_jump = 0.0f, half_at = kInfinity;
  for (int k = -60; k <= 60; ++k) {
    const float s = float(k) * texel / 20.0f;
    const Vec3 p = on_edge + along * s;
    const float v = map->surface_visibility(p), tap = map->visibility(p);
    if (k > -60) {
      max_step = std::max(max_step, std::abs(v - prev_filtered));
      max_jump = std::max(max_jump, std::abs(tap - prev_tap));
      if (prev_filtered < 0.5f && v >= 0.5f) half_at = s;
    }
    if (s < -1.5f * texel) {
      EXPECT_EQ(v, 0.0f) << s / texel;
    }
    if (s > 1.5f * texel) {
      EXPECT_EQ(v, 1.0f) << s / texel;
    }
    prev_filtered = v;
    prev_tap = tap;
  }
  std::printf("edge: filtered step %.4f per texel/20, single tap %.1f, half at %.2f texels\n", max_step, max_jump,
              half_at / texel);
  EXPECT_LE(max_step, std::sqrt(2.0f) / 20.0f + 1e-4f);
  EXPECT_EQ(max_jump, 1.0f);
  EXPECT_LT(std::abs(half_at), texel);
}

// A wide spot (outer angle > 75 degrees) gets a cube and still agrees.
TEST(ShadowMap, WideSpotUsesCube) {
  const Fixture f;
  SpotLight l;
  l.position = {0.3f, 2.8f, 0.5f};
  l.direction = {0, -1, 0};
  l.up = {0, 0, 1};
  l.cos_outer = std::cos(1.4f);
  l.cos_inner = std::cos(1.2f);
  l.intensity = RGB(1.0f);
  const auto map = render_shadow_map(f.raster, l, 64, f.bounds);
  ASSERT_TRUE(map);
  EXPECT_TRUE(map->is_cube());
  expect_agreement(l, "wide spot");
}

}  // namespace
}  // namespace caligo
