#include "volumes/volume_scene.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace caligo {
namespace {

VolumePrimitive fog_sphere(Vec3 c, float r) {
  return {SphereVolumeShape{Sphere::make(c, r, {})}, {RGB(0.1f), RGB(0.5f)}};
}

TEST(VolumeInterval, SphereFromOutsideAndInside) {
  const VolumeShape s = SphereVolumeShape{Sphere::make({0, 0, 5}, 1.0f, {})};
  auto i = volume_hull_interval(s, {{0, 0, 0}, {0, 0, 1}});
  ASSERT_TRUE(i);
  EXPECT_NEAR(i->t0, 4.0f, 1e-5f);
  EXPECT_NEAR(i->t1, 6.0f, 1e-5f);
  // The camera inside: the interval starts at the ray's origin.
  i = volume_hull_interval(s, {{0, 0, 5}, {0, 0, 1}});
  ASSERT_TRUE(i);
  EXPECT_FLOAT_EQ(i->t0, 0.0f);
  EXPECT_NEAR(i->t1, 1.0f, 1e-5f);
  // Pruned by a surface hit before the volume: nothing.
  EXPECT_FALSE(volume_hull_interval(s, {{0, 0, 0}, {0, 0, 1}, 0.0f, 3.0f}));
  // Pruned inside: clipped.
  i = volume_hull_interval(s, {{0, 0, 0}, {0, 0, 1}, 0.0f, 4.5f});
  ASSERT_TRUE(i);
  EXPECT_FLOAT_EQ(i->t1, 4.5f);
}

TEST(VolumeInterval, TransformedBox) {
  const VolumeShape box = BoxVolumeShape{
      Transform::translate({0, 0, 10}) * Transform::rotate(kPi / 4, {0, 0, 1}), {-1, -1, -1}, {1, 1, 1}};
  const auto i = volume_hull_interval(box, {{0, 0, 0}, {0, 0, 1}});
  ASSERT_TRUE(i);
  EXPECT_NEAR(i->t0, 9.0f, 1e-5f);
  EXPECT_NEAR(i->t1, 11.0f, 1e-5f);
  // Rotated 45 degrees about z: along x the box reaches sqrt(2).
  const auto across = volume_hull_interval(box, {{-5, 0, 10}, {1, 0, 0}});
  ASSERT_TRUE(across);
  EXPECT_NEAR(across->t1 - across->t0, 2.0f * std::sqrt(2.0f), 1e-4f);
  EXPECT_FALSE(volume_hull_interval(box, {{-5, 1.5f, 10}, {1, 0, 0}}));
}

TEST(VolumeScene, IntervalsOfOverlappingPrimitives) {
  const VolumeScene scene(
      {fog_sphere({0, 0, 5}, 1.0f), fog_sphere({0, 0, 5.5f}, 1.0f), fog_sphere({3, 0, 5}, 1.0f)});
  VolumeContext scratch;
  scene.intervals({{0, 0, 0}, {0, 0, 1}}, scratch);
  auto v = scratch.intervals;
  std::sort(v.begin(), v.end(), [](auto a, auto b) { return a.primitive < b.primitive; });
  ASSERT_EQ(v.size(), 2u);
  EXPECT_EQ(v[0].primitive, 0u);
  EXPECT_NEAR(v[0].t0, 4.0f, 1e-5f);
  EXPECT_EQ(v[1].primitive, 1u);
  EXPECT_NEAR(v[1].t1, 6.5f, 1e-5f);
}

TEST(VolumeShader, DensityScalesCoefficientsAndFalloffPeaksAtTheCentre) {
  VolumePrimitive p = fog_sphere({0, 0, 0}, 2.0f);
  p.shader.density = 3.0f;
  VolumeContext ctx;
  EXPECT_FLOAT_EQ(shade_volume(p, {0.5f, 0, 0}, ctx).sigma_s.g, 1.5f);
  EXPECT_TRUE(is_homogeneous(p.shader));
  p.shader.field = RadialFalloffDensity{2.0f};
  EXPECT_FALSE(is_homogeneous(p.shader));
  EXPECT_FLOAT_EQ(shade_volume(p, {0, 0, 0}, ctx).sigma_s.g, 1.5f);
  // r = 1 of radius 2: (1 - 0.25)^2.
  EXPECT_NEAR(shade_volume(p, {1, 0, 0}, ctx).sigma_a.r, 0.3f * 0.5625f, 1e-6f);
  EXPECT_FLOAT_EQ(shade_volume(p, {0, 2.1f, 0}, ctx).sigma_a.r, 0.0f);
  // The interval's majorant is the peak: density 3 x sigma_t 0.6.
  append_intervals(p, 0, Ray{{-5, 0, 0}, {1, 0, 0}}, ctx);
  ASSERT_EQ(ctx.intervals.size(), 1u);
  EXPECT_FLOAT_EQ(ctx.intervals[0].sigma_maj.r, 1.8f);
}

// Height fog: 1 up to the base, e^(-(y - base)/H) above, in world space; each interval's
// majorant bounds the density everywhere on it (the lowest end's), however the ray runs.
TEST(VolumeShader, HeightFogThinsUpwardsAndItsMajorantBoundsIt) {
  VolumePrimitive p;
  p.shape = BoxVolumeShape{Transform(), {-5, 0, -5}, {5, 6, 5}};
  p.shader.sigma_s = RGB(0.5f);
  p.shader.field = HeightFalloffDensity{1.0f, 2.0f};
  VolumeContext ctx;
  EXPECT_FALSE(is_homogeneous(p.shader));
  EXPECT_FLOAT_EQ(shade_volume(p, {0, 0.5f, 0}, ctx).sigma_s.g, 0.5f);
  EXPECT_NEAR(shade_volume(p, {2, 3.0f, 1}, ctx).sigma_s.g, 0.5f * std::exp(-1.0f), 1e-6f);
  const Ray rays[] = {{{-6, 5, 0}, normalize(Vec3(1, -0.7f, 0.1f))}, {{-6, 2, 0}, normalize(Vec3(1, 0.3f, 0))},
                      {{0, 3, -6}, {0, 0, 1}}};
  for (const Ray& ray : rays) {
    ctx.intervals.clear();
    append_intervals(p, 0, ray, ctx);
    ASSERT_EQ(ctx.intervals.size(), 1u);
    const VolumeInterval& iv = ctx.intervals[0];
    for (int i = 0; i <= 100; ++i) {
      const float t = iv.t0 + (iv.t1 - iv.t0) * float(i) / 100.0f;
      EXPECT_LE(shade_volume(p, ray.at(t), ctx).sigma_s.g, iv.sigma_maj.g * (1.0f + 1e-5f));
    }
  }
}

}  // namespace
}  // namespace caligo

namespace caligo {
namespace {

// Above the linear-scan limit the BVH answers; both paths must find the same intervals.
TEST(VolumeScene, BvhAndLinearScanAgree) {
  std::vector<VolumePrimitive> many;
  for (int i = 0; i < 40; ++i)
    many.push_back(
        {SphereVolumeShape{Sphere::make({float(i % 7) - 3.0f, float(i / 7) - 3.0f, 5.0f}, 0.6f, {})},
         {RGB(0.1f), RGB(0.1f)}});
  const VolumeScene bvh(many);
  VolumeContext scratch;
  for (int r = 0; r < 100; ++r) {
    const Ray ray{{0, 0, 0},
                  normalize(Vec3(float(r % 10) * 0.07f - 0.3f, float(r / 10) * 0.07f - 0.3f, 1.0f))};
    bvh.intervals(ray, scratch);
    auto found = scratch.intervals;
    std::sort(found.begin(), found.end(), [](auto a, auto b) { return a.primitive < b.primitive; });
    std::vector<VolumeInterval> expected;
    for (uint32_t i = 0; i < many.size(); ++i)
      if (const auto range = volume_hull_interval(many[i].shape, ray))
        expected.push_back({range->t0, range->t1, i});
    ASSERT_EQ(found.size(), expected.size()) << "ray " << r;
    for (size_t k = 0; k < found.size(); ++k) {
      EXPECT_EQ(found[k].primitive, expected[k].primitive);
      EXPECT_EQ(found[k].t0, expected[k].t0);
    }
  }
}

}  // namespace
}  // namespace caligo
