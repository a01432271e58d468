// The density noise: periodic, bounded, mean one, deterministic, and wired into shade_volume.
#include "volumes/noise.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/rng.h"
#include "volumes/volume.h"

namespace caligo {
namespace {

constexpr int kN = NoiseTexture::kSize;

Vec3 random_point(Pcg32& rng, float extent) {
  return {extent * (2 * rng.next_float() - 1), extent * (2 * rng.next_float() - 1),
          extent * (2 * rng.next_float() - 1)};
}

TEST(NoiseTexture, ValuesHaveZeroMeanAndPeakMagnitudeOne) {
  const auto& v = NoiseTexture::shared().values();
  ASSERT_EQ(v.size(), size_t(kN) * kN * kN);
  double sum = 0.0;
  float peak = 0.0f;
  for (float x : v) {
    sum += x;
    peak = std::max(peak, std::abs(x));
  }
  EXPECT_NEAR(sum / double(v.size()), 0.0, 1e-6);
  EXPECT_FLOAT_EQ(peak, 1.0f);
}

TEST(NoiseTexture, InterpolatesThroughLatticeValues) {
  const NoiseTexture& t = NoiseTexture::shared();
  for (int z : {0, 5, 31})
    for (int x : {0, 7, 30}) {
      const float expected = t.values()[(size_t(z) * kN + 3) * kN + size_t(x)];
      EXPECT_FLOAT_EQ(t.lookup(Vec3(float(x), 3.0f, float(z))), expected);
    }
}

TEST(NoiseTexture, IsPeriodicInEveryAxis) {
  const NoiseTexture& t = NoiseTexture::shared();
  Pcg32 rng(1, 2);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 p = random_point(rng, 40.0f);
    const float v = t.lookup(p);
    EXPECT_NEAR(t.lookup(p + Vec3(kN, 0, 0)), v, 1e-4f);
    EXPECT_NEAR(t.lookup(p + Vec3(0, -kN, 0)), v, 1e-4f);
    EXPECT_NEAR(t.lookup(p + Vec3(0, 0, 3 * kN)), v, 1e-4f);
  }
}

// Two calls, the same texture and the same values (hash-built, no global random state).
TEST(NoiseTexture, IsDeterministic) {
  EXPECT_EQ(&NoiseTexture::shared(), &NoiseTexture::shared());
  const NoiseModulation n{0.7f, 0.6f, {}, {0.1f, 0.2f, 0.3f}};
  Pcg32 rng(9, 9);
  for (int i = 0; i < 100; ++i) {
    const Vec3 p = random_point(rng, 10.0f);
    EXPECT_EQ(noise_density(n, p), noise_density(n, p));
  }
  // Smooth: a millimetre moves the density by far less than its range.
  EXPECT_NEAR(noise_density(n, {1, 2, 3}), noise_density(n, {1.001f, 2, 3}), 0.01f);
}

TEST(NoiseDensity, StaysWithinOneMinusToOnePlusAmplitudeAndUsesTheRange) {
  for (float a : {0.0f, 0.3f, 1.0f}) {
    const NoiseModulation n{2.0f, a, {}, {}};
    Pcg32 rng(4, 7);
    float lo = 10.0f, hi = -10.0f;
    for (int i = 0; i < 20000; ++i) {
      const float d = noise_density(n, random_point(rng, 20.0f));
      lo = std::min(lo, d);
      hi = std::max(hi, d);
    }
    EXPECT_GE(lo, 1.0f - a - 1e-6f);
    EXPECT_LE(hi, 1.0f + a + 1e-6f);
    EXPECT_LE(hi, noise_density_max(n));
    // Not a constant: at least half the allowed swing is reached on each side.
    if (a > 0.0f) {
      EXPECT_LT(lo, 1.0f - 0.5f * a);
      EXPECT_GT(hi, 1.0f + 0.5f * a);
    }
  }
}

// Over one period (kN / scale metres per axis) the mean is 1 exactly in theory (zero-mean
// lattice, symmetric fade); a 64^3 midpoint grid estimates it to well within 0.5 %.
TEST(NoiseDensity, MeanOverAPeriodIsOne) {
  const NoiseModulation n{0.5f, 0.8f, {}, {}};
  const float period = kN / n.scale;
  constexpr int kGrid = 64;
  double sum = 0.0;
  for (int z = 0; z < kGrid; ++z)
    for (int y = 0; y < kGrid; ++y)
      for (int x = 0; x < kGrid; ++x)
        sum += noise_density(n, Vec3(x + 0.37f, y + 0.61f, z + 0.13f) * (period / kGrid));
  EXPECT_NEAR(sum / (double(kGrid) * kGrid * kGrid), 1.0, 0.005);
}

TEST(NoiseDensity, OffsetShiftsThePattern) {
  const NoiseModulation still{1.0f, 0.5f, {}, {}};
  const NoiseModulation moved{1.0f, 0.5f, {}, {0.3f, -1.2f, 2.0f}};
  EXPECT_FLOAT_EQ(noise_density(moved, Vec3(1.3f, -0.2f, 5.0f)),
                  noise_density(still, Vec3(1.0f, 1.0f, 3.0f)));
}

TEST(VolumeShaderNoise, ModulatesDensityAndBoundsTheMajorant) {
  VolumePrimitive v{BoxVolumeShape{Transform(), Vec3(-10.0f), Vec3(10.0f)},
                    VolumeShader{RGB(0.1f), RGB(0.4f), RGB(0.0f), 2.0f}};
  EXPECT_TRUE(is_homogeneous(v.shader));
  const NoiseModulation n{0.8f, 0.7f, {}, {}};
  v.shader.noise = n;
  EXPECT_FALSE(is_homogeneous(v.shader));
  // The interval's majorant bounds the noise's peak, and the interval is not homogeneous.
  VolumeContext ctx;
  append_intervals(v, 0, Ray{{-20, 0, 0}, {1, 0, 0}}, ctx);
  ASSERT_EQ(ctx.intervals.size(), 1u);
  const RGB majorant = ctx.intervals[0].sigma_maj;
  EXPECT_FLOAT_EQ(majorant.r, 0.5f * 2.0f * 1.7f);
  EXPECT_FALSE(ctx.intervals[0].homogeneous);
  Pcg32 rng(5, 5);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 p = random_point(rng, 9.0f);
    const MediumSample m = shade_volume(v, p, ctx);
    EXPECT_NEAR(m.sigma_s.g, 0.4f * 2.0f * noise_density(n, p), 1e-6f);
    EXPECT_LE(m.sigma_t().r, majorant.r + 1e-6f);
  }
}

}  // namespace
}  // namespace caligo
