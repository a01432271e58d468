// The tracking estimators against closed forms: Beer-Lambert through chromatic slabs, the
// probability and weight of scattering in a segment, emission gathered on the way, and ratio
// tracking against a fine deterministic march through a heterogeneous sphere. Every mean is
// checked within 4 standard errors of its own sample (the tolerance the noise requires).
#include "tracking/tracking.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/test_stat.h"

namespace caligo {
namespace {

VolumePrimitive box(Vec3 lo, Vec3 hi, RGB sigma_a, RGB sigma_s, RGB emission = {}) {
  return {BoxVolumeShape{{}, lo, hi}, {sigma_a, sigma_s, emission}};
}

using testing::Stat;

#define EXPECT_WITHIN_4SE(stat, expected)                                                         \
  EXPECT_NEAR((stat).mean(), (expected), 4.0 * (stat).se() + 1e-7) << "se " << (stat).se()

TEST(Tracking, RatioTrackingIsBeerLambertPerChannel) {
  const RGB sa(0.3f, 0.6f, 1.2f), ss(0.2f, 0.4f, 1.8f);
  const VolumeScene scene({box({-1, -1, 2}, {1, 1, 3.5f}, sa, ss)});
  MarchScratch scratch;
  Pcg32 rng(7, 1);
  // A non-unit direction: t is in units of its length, coefficients scale with it.
  const Ray ray{{0, 0, 0}, {0, 0, 2}};
  Stat s[3];
  for (int i = 0; i < 20000; ++i) {
    const RGB t = track_transmittance(scene, ray, {}, scratch, rng, -1, /*residual=*/false);
    for (int c = 0; c < 3; ++c) s[c].add(t[c]);
  }
  for (int c = 0; c < 3; ++c) EXPECT_WITHIN_4SE(s[c], std::exp(-(sa[c] + ss[c]) * 1.5));
  EXPECT_GT(s[2].se(), 0.0);  // the chromatic slab's thin channels are estimated with noise
}

// Residual ratio tracking's control is the slab's own extinction: the residual majorant is 0,
// so the estimate is Beer-Lambert exactly (float rounding), with no collision and no lookup.
TEST(Tracking, ResidualRatioTrackingIsExactInAHomogeneousSlab) {
  const RGB sa(0.3f, 0.6f, 1.2f), ss(0.2f, 0.4f, 1.8f);
  const VolumeScene scene({box({-1, -1, 2}, {1, 1, 3.5f}, sa, ss)});
  MarchScratch scratch;
  Pcg32 rng(7, 1);
  const Ray ray{{0, 0, 0}, {0, 0, 2}};
  for (int i = 0; i < 8; ++i) {
    const RGB t = track_transmittance(scene, ray, {}, scratch, rng);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(t[c], std::exp(-(sa[c] + ss[c]) * 1.5), 1e-6f);
  }
  EXPECT_EQ(scratch.shader_evaluations, 0u);
}

TEST(Tracking, RatioTrackingMatchesAFineMarchThroughAHeterogeneousSphere) {
  VolumePrimitive puff{SphereVolumeShape{Sphere::make({0, 0, 3}, 1.0f, Transform())},
                       {RGB(0.5f), RGB(2.0f, 1.0f, 3.0f)}};
  puff.shader.field = RadialFalloffDensity{2.0f};
  const VolumeScene scene({puff});
  MarchScratch scratch;
  MarchSettings fine;
  fine.auto_step_fraction = 1.0f / 4096.0f;
  const Ray ray{{0.2f, 0.1f, 0}, normalize(Vec3(0, 0, 1))};
  const RGB marched = march_transmittance(scene, ray, 0.5f, fine, scratch);  // midpoint rule, error ~1e-7
  Pcg32 rng(11, 3);
  Stat s[3];
  for (int i = 0; i < 20000; ++i) {
    const RGB t = track_transmittance(scene, ray, {}, scratch, rng);
    for (int c = 0; c < 3; ++c) s[c].add(t[c]);
  }
  for (int c = 0; c < 3; ++c) EXPECT_WITHIN_4SE(s[c], marched[c]);
}

// Height fog (world-space exponential falloff above a base) tracked along a rising ray: its
// majorant is the density at the stretch's lowest end, and ratio tracking's mean is
// exp(-sigma_t x the closed-form integral of the density).
TEST(Tracking, RatioTrackingMatchesTheClosedFormThroughHeightFog) {
  VolumePrimitive fog = box({-3, 0, 1}, {3, 4, 6}, RGB(0.2f), RGB(0.6f, 0.9f, 0.3f));
  fog.shader.field = HeightFalloffDensity{0.8f, 0.5f};
  const VolumeScene scene({fog});
  MarchScratch scratch;
  const Ray ray{{0.3f, 0.1f, 0}, normalize(Vec3(0.1f, 0.5f, 1.0f))};
  const float t0 = 1.0f / ray.direction.z;  // enters at z = 1
  const float t1 = std::min(6.0f / ray.direction.z, (4.0f - 0.1f) / ray.direction.y);
  const float depth = height_fog_depth(std::get<HeightFalloffDensity>(fog.shader.field), ray.origin.y,
                                       ray.direction.y, t0, t1);
  Pcg32 rng(5, 9);
  Stat s[3];
  for (int i = 0; i < 20000; ++i) {
    const RGB t = track_transmittance(scene, ray, {}, scratch, rng);
    for (int c = 0; c < 3; ++c) s[c].add(t[c]);
  }
  const RGB sigma_t = RGB(0.2f) + RGB(0.6f, 0.9f, 0.3f);
  for (int c = 0; c < 3; ++c) EXPECT_WITHIN_4SE(s[c], std::exp(-sigma_t[c] * depth));
}

// In a homogeneous slab of length L: E[weight_c; scattered] = sigma_s,c (1 - exp(-sigma_t,c L)) /
// sigma_t,c and E[weight_c; passed] = exp(-sigma_t,c L), for any history the probabilities follow.
void check_free_flight(RGB sa, RGB ss, RGB history) {
  const float length = 1.5f;
  const VolumeScene scene({box({-1, -1, 2}, {1, 1, 2 + length}, sa, ss)});
  MarchScratch scratch;
  Pcg32 rng(3, 5);
  const Ray ray{{0, 0, 0}, {0, 0, 1}};
  Stat scattered[3], passed[3], mean_t;
  for (int i = 0; i < 40000; ++i) {
    ASSERT_TRUE(collect_spans(scene, ray, {}, scratch));
    const TrackedSegment seg = track_free_flight(scene, ray, history, true, false, scratch, rng);
    const bool s = seg.outcome == TrackedSegment::Outcome::kScattered;
    const bool p = seg.outcome == TrackedSegment::Outcome::kPassed;
    for (int c = 0; c < 3; ++c) {
      scattered[c].add(s ? seg.weight[c] : 0.0);
      passed[c].add(p ? seg.weight[c] : 0.0);
    }
    // The mean collision distance in the red channel, weighted (an integral of t sigma_s T).
    mean_t.add(s ? double(seg.weight.r) * (seg.t - 2.0) : 0.0);
  }
  for (int c = 0; c < 3; ++c) {
    const double st = sa[c] + ss[c];
    EXPECT_WITHIN_4SE(scattered[c], ss[c] / st * -std::expm1(-st * length));
    EXPECT_WITHIN_4SE(passed[c], std::exp(-st * length));
  }
  // Integral over [0, L] of x sigma_s e^{-sigma_t x} dx.
  const double st = sa.r + ss.r, e = std::exp(-st * length);
  EXPECT_WITHIN_4SE(mean_t, ss.r / (st * st) * (1.0 - e * (1.0 + st * length)));
}

TEST(Tracking, FreeFlightIsUnbiasedInAGreyAbsorbingSlab) { check_free_flight(RGB(0.4f), RGB(1.1f), RGB(1.0f)); }

TEST(Tracking, SpectralTrackingIsUnbiasedInAChromaticSlabForAnyHistory) {
  check_free_flight(RGB(0.05f, 0.1f, 0.0f), RGB(0.5f, 1.0f, 2.0f), RGB(1.0f));
  check_free_flight(RGB(0.05f, 0.1f, 0.0f), RGB(0.5f, 1.0f, 2.0f), RGB(3.0f, 0.2f, 1.0f));
}

TEST(Tracking, AlbedoOneGreyMediumIsDeltaTrackingWithUnitWeights) {
  const VolumeScene scene({box({-1, -1, 1}, {1, 1, 4}, RGB(0.0f), RGB(1.3f))});
  MarchScratch scratch;
  Pcg32 rng(1, 1);
  const Ray ray{{0, 0, 0}, {0, 0, 1}};
  for (int i = 0; i < 200; ++i) {
    ASSERT_TRUE(collect_spans(scene, ray, {}, scratch));
    const TrackedSegment seg = track_free_flight(scene, ray, RGB(1.0f), true, false, scratch, rng);
    ASSERT_NE(seg.outcome, TrackedSegment::Outcome::kAbsorbed);
    // The majorant is sigma_t = sigma_s: every collision scatters, with weight sigma_s / mu = 1.
    EXPECT_FLOAT_EQ(seg.weight.r, 1.0f);
    EXPECT_FLOAT_EQ(seg.weight.b, 1.0f);
  }
}

TEST(Tracking, EmissionGatheredOnTheWayIsTheIntegralOfTransmittanceTimesEmission) {
  const RGB sa(0.5f, 1.0f, 2.0f), ss(0.5f), emission(2.0f, 1.0f, 0.5f);
  const float length = 2.0f;
  const VolumeScene scene({box({-1, -1, 1}, {1, 1, 1 + length}, sa, ss, emission)});
  MarchScratch scratch;
  Pcg32 rng(9, 2);
  const Ray ray{{0, 0, 0}, {0, 0, 1}};
  Stat s[3];
  for (int i = 0; i < 40000; ++i) {
    ASSERT_TRUE(collect_spans(scene, ray, {}, scratch));
    // No scattering: emission along the whole segment, attenuated by its transmittance.
    const TrackedSegment seg = track_free_flight(scene, ray, RGB(1.0f), false, true, scratch, rng);
    for (int c = 0; c < 3; ++c) s[c].add(seg.emission[c]);
  }
  for (int c = 0; c < 3; ++c) {
    const double st = sa[c] + ss[c];
    EXPECT_WITHIN_4SE(s[c], emission[c] / st * -std::expm1(-st * length));
  }
}

TEST(Tracking, AnEmptyOrVacuumRayPassesWithUnitWeight) {
  const VolumeScene scene({box({-1, -1, 1}, {1, 1, 2}, RGB(0.0f), RGB(0.0f))});
  MarchScratch scratch;
  Pcg32 rng;
  const Ray away{{0, 0, 0}, {0, 0, -1}};
  EXPECT_EQ(track_transmittance(scene, away, {}, scratch, rng).r, 1.0f);
}

}  // namespace
}  // namespace caligo
