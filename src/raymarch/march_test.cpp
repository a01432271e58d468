#include "raymarch/march.h"

#include <gtest/gtest.h>

#include <cmath>

namespace caligo {
namespace {

VolumePrimitive box(Vec3 lo, Vec3 hi, RGB sigma_a, RGB sigma_s, RGB emission = {}) {
  return {BoxVolumeShape{{}, lo, hi}, {sigma_a, sigma_s, emission}};
}

TEST(March, SlabTransmittanceIsBeerLambert) {
  const VolumeScene scene({box({-1, -1, 2}, {1, 1, 3.5f}, RGB(0.3f, 0.6f, 1.2f), RGB(0.2f))});
  MarchScratch scratch;
  TransmittanceRecord record;
  const Ray ray{{0, 0, 0}, {0, 0, 1}};
  march(scene, ray, 0.5f, {}, scratch, record);
  ASSERT_EQ(record.steps().size(), 1u);  // homogeneous: one step
  const RGB t = record.transmittance_end();
  EXPECT_NEAR(t.r, std::exp(-0.5f * 1.5f), 1e-3f * std::exp(-0.5f * 1.5f));
  EXPECT_NEAR(t.b, std::exp(-1.4f * 1.5f), 1e-3f * std::exp(-1.4f * 1.5f));
  const RGB shadow = march_transmittance(scene, ray, 0.5f, {}, scratch);
  EXPECT_NEAR(shadow.g, t.g, 1e-6f);
}

TEST(March, TwoHalfDensityOverlapsEqualOneFullDensity) {
  const RGB sa(0.1f, 0.2f, 0.3f), ss(0.8f, 0.4f, 0.2f);
  const VolumeScene half(
      {box({-1, -1, 1}, {1, 1, 4}, sa * 0.5f, ss * 0.5f), box({-1, -1, 1}, {1, 1, 4}, sa * 0.5f, ss * 0.5f)});
  const VolumeScene full({box({-1, -1, 1}, {1, 1, 4}, sa, ss)});
  MarchScratch scratch;
  TransmittanceRecord a, b;
  const Ray ray{{0.2f, 0.1f, 0}, normalize(Vec3(0.1f, 0, 1))};
  march(half, ray, 0.5f, {}, scratch, a);
  march(full, ray, 0.5f, {}, scratch, b);
  ASSERT_EQ(a.steps().size(), b.steps().size());
  for (float t : {1.5f, 2.5f, 3.9f, 10.0f}) {
    EXPECT_NEAR(a.transmittance(t).r, b.transmittance(t).r, 1e-6f);
    EXPECT_NEAR(a.transmittance(t).b, b.transmittance(t).b, 1e-6f);
  }
  EXPECT_NEAR(a.scatter_weight_total(), b.scatter_weight_total(), 1e-6f);
  // The phase mixture of the two halves has two lobes weighing one half each.
  const auto lobes = a.lobes(a.steps()[0]);
  ASSERT_EQ(lobes.size(), 2u);
  EXPECT_NEAR(lobes[0].weight.r + lobes[1].weight.r, 1.0f, 1e-6f);
  EXPECT_NEAR(lobes[0].weight.b + lobes[1].weight.b, 1.0f, 1e-6f);
}

TEST(March, OverlapSplitsIntoSpansAndStopsAtTheSurface) {
  const VolumeScene scene(
      {box({-1, -1, 1}, {1, 1, 3}, RGB(0.1f), RGB(0.1f)), box({-1, -1, 2}, {1, 1, 5}, RGB(0.2f), RGB(0.0f))});
  MarchScratch scratch;
  TransmittanceRecord record;
  march(scene, {{0, 0, 0}, {0, 0, 1}, 0.0f, 4.0f}, 0.5f, {}, scratch, record);  // a surface at t = 4
  ASSERT_EQ(record.steps().size(), 3u);
  EXPECT_FLOAT_EQ(record.steps()[1].sigma_t.g, 0.4f);
  EXPECT_FLOAT_EQ(record.t_end(), 4.0f);
  EXPECT_NEAR(record.transmittance_end().r, std::exp(-(0.2f * 2 + 0.2f * 2)), 1e-5f);
}

TEST(March, EmissionOfAnAbsorbingSlab) {
  // L = e / sigma_a * (1 - exp(-sigma_a d)) for a slab that absorbs and emits.
  const VolumeScene scene({box({-1, -1, 1}, {1, 1, 3}, RGB(0.5f), RGB(0.0f), RGB(2.0f))});
  MarchScratch scratch;
  TransmittanceRecord record;
  march(scene, {{0, 0, 0}, {0, 0, 1}}, 0.5f, {}, scratch, record);
  EXPECT_NEAR(record.emission().r, 2.0f / 0.5f * (1.0f - std::exp(-1.0f)), 1e-5f);
}

TEST(March, HeterogeneousStepsConvergeToTheIntegral) {
  VolumePrimitive puff{SphereVolumeShape{Sphere::make({0, 0, 5}, 2.0f, {})}, {RGB(0.5f), RGB(0.5f)}};
  puff.shader.field = RadialFalloffDensity{1.0f};
  puff.shader.step_size = 0.01f;
  const VolumeScene scene({puff});
  MarchScratch scratch;
  TransmittanceRecord record;
  march(scene, {{0, 0, 0}, {0, 0, 1}}, 0.5f, {}, scratch, record);
  EXPECT_GE(record.steps().size(), 400u);
  // Along the diameter: integral of sigma_t (1 - r^2/R^2) over [-R, R] = sigma_t * 4R/3.
  EXPECT_NEAR(record.transmittance_end().g, std::exp(-1.0f * 4.0f * 2.0f / 3.0f), 1e-4f);
}

// A step far below the span's length (a hostile step_size, or a tiny voxel) makes more steps
// than an int holds: the count must saturate at max_steps_per_span, not wrap to one step.
TEST(March, TinyStepSizeSaturatesAtTheStepLimit) {
  VolumePrimitive puff{SphereVolumeShape{Sphere::make({0, 0, 5}, 2.0f, {})}, {RGB(0.5f), RGB(0.5f)}};
  puff.shader.field = RadialFalloffDensity{1.0f};
  puff.shader.step_size = 1e-30f;
  const VolumeScene scene({puff});
  MarchSettings settings;
  settings.max_steps_per_span = 100;
  MarchScratch scratch;
  TransmittanceRecord record;
  march(scene, {{0, 0, 0}, {0, 0, 1}}, 0.5f, settings, scratch, record);
  EXPECT_EQ(record.steps().size(), 100u);
  // 100 midpoint steps of the diameter integral sigma_t * 4R/3.
  EXPECT_NEAR(record.transmittance_end().g, std::exp(-1.0f * 4.0f * 2.0f / 3.0f), 1e-3f);
}

TEST(March, StopsAtTheOpacityThreshold) {
  const VolumeScene scene({box({-1, -1, 1}, {1, 1, 2}, RGB(20.0f), RGB(0.0f)),
                           box({-1, -1, 3}, {1, 1, 4}, RGB(1.0f), RGB(1.0f))});
  MarchScratch scratch;
  TransmittanceRecord record;
  march(scene, {{0, 0, 0}, {0, 0, 1}}, 0.5f, {}, scratch, record);
  EXPECT_EQ(record.steps().size(), 1u);  // T = e^-20 after the first box: nothing behind matters
  EXPECT_TRUE(march_transmittance(scene, {{0, 0, 0}, {0, 0, 1}}, 0.5f, {}, scratch).is_black());
}

}  // namespace
}  // namespace caligo
