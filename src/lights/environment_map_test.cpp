// Environment maps (environment_map.h), the environment light built on them and the generated
// sky: the lat-long convention, bilinear lookup, a pdf that integrates to one and that the
// samples follow (chi-squared over a binned sphere not aligned with the pixels), an unbiased
// estimator of the map's integral, zero rows and black maps, rotation, and the sky's sun.
#include "lights/environment_map.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/math.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "core/testing/chi_squared.h"
#include "lights/light_sample.h"
#include "lights/sky_generate.h"

namespace caligo {
namespace {

void expect_vec_near(Vec3 a, Vec3 b, float tol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

// 32 x 16, not 2:1-symmetric in anything: black top four rows (a black region the sampler must
// avoid), a horizontal gradient, a bright block, isolated black pixels.
EnvironmentMap test_map() {
  const int w = 32, h = 16;
  std::vector<RGB> px(size_t(w * h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      RGB c = y < 4 ? RGB(0.0f) : RGB(0.2f + 0.05f * float(x), 0.3f, 0.1f + 0.02f * float(y));
      if (x >= 20 && x < 23 && y >= 6 && y < 8) c = RGB(40.0f, 30.0f, 20.0f);
      if ((x * 7 + y * 3) % 11 == 0) c = RGB(0.0f);
      px[size_t(y * w + x)] = c;
    }
  return EnvironmentMap(w, h, std::move(px));
}

// Midpoint quadrature in (phi, cos theta) of f over the sphere, n_phi x n_cos cells.
template <typename F>
double integrate_sphere(int n_phi, int n_cos, F f) {
  double sum = 0.0;
  for (int j = 0; j < n_cos; ++j) {
    const float z = 1.0f - 2.0f * (float(j) + 0.5f) / float(n_cos);
    const float s = safe_sqrt(1.0f - z * z);
    for (int i = 0; i < n_phi; ++i) {
      const float phi = 2.0f * kPi * (float(i) + 0.5f) / float(n_phi);
      sum += f(Vec3{s * std::cos(phi), z, s * std::sin(phi)});
    }
  }
  return sum * 4.0 * M_PI / (double(n_phi) * n_cos);
}

TEST(LatLong, ConventionPinsTheAxes) {
  const auto uv = [](Vec3 w) { return direction_to_latlong(w); };
  EXPECT_NEAR(uv({0, 0, -1}).x, 0.5f, 1e-6f);  // the image centre looks along -Z
  EXPECT_NEAR(uv({0, 0, -1}).y, 0.5f, 1e-6f);
  EXPECT_NEAR(uv({1, 0, 0}).x, 0.75f, 1e-6f);
  EXPECT_NEAR(uv({-1, 0, 0}).x, 0.25f, 1e-6f);
  EXPECT_NEAR(uv({0, 0, 1}).x, 0.0f, 1e-6f);  // the seam, wrapped into [0, 1)
  EXPECT_NEAR(uv({0, 1, 0}).y, 0.0f, 1e-6f);  // the top row is the zenith
  EXPECT_NEAR(uv({0, -1, 0}).y, 1.0f, 1e-6f);
  Pcg32 rng(3, 5);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 w = sample_uniform_sphere({rng.next_float(), rng.next_float()});
    const Vec2 t = direction_to_latlong(w);
    ASSERT_GE(t.x, 0.0f);
    ASSERT_LT(t.x, 1.0f);
    expect_vec_near(latlong_to_direction(t), w, 2e-5f);
  }
}

TEST(EnvironmentMap, LookupIsBilinearBetweenPixelCentres) {
  // 4 x 2: the right-hand pixel of each row bright.
  std::vector<RGB> px = {RGB(0), RGB(0), RGB(0), RGB(4), RGB(1), RGB(1), RGB(1), RGB(3)};
  const EnvironmentMap map(4, 2, px);
  // Pixel centres return the pixel: (x + 0.5) / 4, (y + 0.5) / 2.
  EXPECT_NEAR(map.lookup(latlong_to_direction({3.5f / 4, 0.25f})).r, 4.0f, 1e-4f);
  EXPECT_NEAR(map.lookup(latlong_to_direction({1.5f / 4, 0.75f})).r, 1.0f, 1e-4f);
  // Halfway between two centres in u: the mean; across the seam it wraps (x = 3 and x = 0).
  EXPECT_NEAR(map.lookup(latlong_to_direction({3.0f / 4, 0.25f})).r, 2.0f, 1e-4f);
  EXPECT_NEAR(map.lookup(latlong_to_direction({0.0f, 0.25f})).r, 2.0f, 1e-4f);
  // Halfway between rows: the mean of the two; above the top row's centre it clamps.
  EXPECT_NEAR(map.lookup(latlong_to_direction({3.5f / 4, 0.5f})).r, 3.5f, 1e-4f);
  EXPECT_NEAR(map.lookup({0, 1, 0}).r, map.lookup(latlong_to_direction({0.0f, 0.0f})).r, 1e-4f);
}

TEST(EnvironmentMap, ConstantMapIsUniformOnTheSphere) {
  const EnvironmentMap map(8, 4, std::vector<RGB>(32, RGB(0.5f)));
  Pcg32 rng(1, 1);
  for (int i = 0; i < 2000; ++i) {
    const Vec2 u{rng.next_float(), rng.next_float()};
    EXPECT_NEAR(map.pdf(sample_uniform_sphere(u)), kInv4Pi, 1e-5f);
    const auto s = map.sample(u);
    ASSERT_TRUE(s);
    EXPECT_NEAR(s->pdf, kInv4Pi, 1e-5f);
    EXPECT_NEAR(length(s->w), 1.0f, 1e-5f);
  }
  EXPECT_NEAR(map.integral().r, 4.0f * kPi * 0.5f, 1e-4f);
  EXPECT_NEAR(map.mean().g, 0.5f, 1e-6f);
}

TEST(EnvironmentMap, PdfIntegratesToOne) {
  const EnvironmentMap map = test_map();
  EXPECT_NEAR(integrate_sphere(1024, 1024, [&](Vec3 w) { return map.pdf(w); }), 1.0, 2e-3);
  // The integral of the pixels agrees with a quadrature of the bilinear lookup (the filter
  // preserves the mean up to the pole clamping).
  EXPECT_NEAR(integrate_sphere(1024, 1024, [&](Vec3 w) { return map.lookup(w).g; }) / map.integral().g, 1.0, 0.01);
}

// 200,000 samples into 16 (cos theta) x 24 (phi) equal-area bins; expected counts from a 16 x 16
// midpoint quadrature of pdf() inside each bin.
TEST(EnvironmentMap, SamplesFollowThePdf) {
  const EnvironmentMap map = test_map();
  constexpr int kCos = 16, kPhi = 24, kSub = 16, kN = 200000;
  std::vector<double> observed(kCos * kPhi, 0.0), expected(kCos * kPhi, 0.0);
  const auto bin = [&](Vec3 w) {
    const int j = std::clamp(int((1.0f - w.y) * 0.5f * kCos), 0, kCos - 1);
    float phi = std::atan2(w.z, w.x);
    if (phi < 0.0f) phi += 2.0f * kPi;
    const int i = std::clamp(int(phi / (2.0f * kPi) * kPhi), 0, kPhi - 1);
    return j * kPhi + i;
  };
  for (int j = 0; j < kCos; ++j)
    for (int i = 0; i < kPhi; ++i) {
      double sum = 0.0;
      for (int b = 0; b < kSub; ++b)
        for (int a = 0; a < kSub; ++a) {
          const float z = 1.0f - 2.0f * (float(j) + (float(b) + 0.5f) / kSub) / kCos;
          const float phi = 2.0f * kPi * (float(i) + (float(a) + 0.5f) / kSub) / kPhi;
          const float s = safe_sqrt(1.0f - z * z);
          sum += map.pdf({s * std::cos(phi), z, s * std::sin(phi)});
        }
      expected[size_t(j * kPhi + i)] = sum / (kSub * kSub) * (4.0 * M_PI / (kCos * kPhi)) * kN;
    }
  Pcg32 rng(17, 2);
  int mismatched = 0;
  for (int n = 0; n < kN; ++n) {
    const auto s = map.sample({rng.next_float(), rng.next_float()});
    ASSERT_TRUE(s);
    observed[size_t(bin(s->w))] += 1.0;
    if (std::abs(s->pdf - map.pdf(s->w)) > 1e-4f * s->pdf) ++mismatched;  // only on cell edges
  }
  EXPECT_LT(mismatched, kN / 1000);
  EXPECT_GT(test_stats::chi2_p_value(observed, expected), 1e-3);
}

// The four black top rows: only the last of them (bordering a lit row, so its bilinear lookup is
// partly lit) may be sampled, and never above it.
TEST(EnvironmentMap, BlackRowsAreNotSampled) {
  const EnvironmentMap map = test_map();
  const float lowest_cos = std::cos(kPi * 3.0f / 16.0f);
  Pcg32 rng(5, 9);
  for (int n = 0; n < 20000; ++n) {
    const auto s = map.sample({rng.next_float(), rng.next_float()});
    ASSERT_TRUE(s);
    ASSERT_LE(s->w.y, lowest_cos + 1e-5f);
  }
  EXPECT_EQ(map.pdf({0, 1, 0}), 0.0f);
}

// lookup / pdf estimates the integral of the lookup without bias: the pdf is positive wherever
// the bilinear lookup is, also in black pixels next to lit ones. 4 standard errors (estimated
// from the same samples).
TEST(EnvironmentMap, ImportanceSamplingIsUnbiased) {
  const EnvironmentMap map = test_map();
  const double exact = integrate_sphere(2048, 2048, [&](Vec3 w) { return map.lookup(w).luminance(); });
  Pcg32 rng(23, 4);
  constexpr int kN = 100000;
  double sum = 0.0, sum2 = 0.0;
  for (int n = 0; n < kN; ++n) {
    const auto s = map.sample({rng.next_float(), rng.next_float()});
    ASSERT_TRUE(s);
    const double f = map.lookup(s->w).luminance() / s->pdf;
    sum += f;
    sum2 += f * f;
  }
  const double mean = sum / kN, se = std::sqrt((sum2 / kN - mean * mean) / kN);
  EXPECT_NEAR(mean, exact, 4.0 * se + 1e-3 * exact) << "standard error " << se;
}

TEST(EnvironmentMap, BlackMapCannotBeSampled) {
  const EnvironmentMap map(4, 2, std::vector<RGB>(8, RGB(0.0f)));
  EXPECT_TRUE(map.is_black());
  EXPECT_FALSE(map.sample({0.3f, 0.6f}));
  EXPECT_EQ(map.pdf({0, 0, -1}), 0.0f);
  EXPECT_EQ(map.integral(), RGB(0.0f));
}

TEST(EnvironmentMap, RejectsBadPixels) {
  EXPECT_THROW(EnvironmentMap(0, 1, {}), std::invalid_argument);
  EXPECT_THROW(EnvironmentMap(2, 1, {RGB(1.0f)}), std::invalid_argument);
  EXPECT_THROW(EnvironmentMap(2, 1, {RGB(1.0f), RGB(-1.0f, 0.0f, 0.0f)}), std::invalid_argument);
  EXPECT_THROW(EnvironmentMap(2, 1, {RGB(1.0f), RGB(std::nanf(""))}), std::invalid_argument);
  EXPECT_THROW(EnvironmentMap(2, 1, {RGB(1.0f), RGB(kInfinity)}), std::invalid_argument);
  EXPECT_THROW(EnvironmentMap(2, 1, {RGB(3e38f), RGB(3e38f)}), std::invalid_argument);  // integral overflows
}

// ---- the environment light ----

EnvironmentLight map_light(float rotation_degrees) {
  EnvironmentLight l{RGB(2.0f)};
  l.map = std::make_shared<const EnvironmentMap>(test_map());
  l.cos_rotation = std::cos(radians(rotation_degrees));
  l.sin_rotation = std::sin(radians(rotation_degrees));
  return l;
}

TEST(EnvironmentLight, RotationTurnsTheMapAboutY) {
  const EnvironmentLight plain = map_light(0.0f), turned = map_light(90.0f);
  // R_y(90) takes +X to -Z and +Z to +X: what the map shows along +X appears along -Z.
  const Vec3 dirs[] = {{1, 0, 0}, {0.6f, 0.8f, 0}, {0.36f, -0.48f, 0.8f}};
  for (Vec3 w : dirs) {
    const Vec3 turned_w{w.z, w.y, -w.x};
    const RGB a = escaped_radiance(plain, w), b = escaped_radiance(turned, turned_w);
    EXPECT_NEAR(a.r, b.r, 1e-4f * a.r + 1e-6f);
    EXPECT_NEAR(light_pdf(plain, {}, w, {}, {}), light_pdf(turned, {}, turned_w, {}, {}), 1e-5f);
  }
  EXPECT_EQ(escaped_radiance(plain, {1, 0, 0}), plain.map->lookup({1, 0, 0}) * 2.0f);
}

TEST(EnvironmentLight, SampleAgreesWithPdfAndEscapedRadiance) {
  const EnvironmentLight l = map_light(37.0f);
  Pcg32 rng(8, 8);
  int mismatched = 0;
  for (int n = 0; n < 5000; ++n) {
    const auto s = sample_light(l, {1, 2, 3}, {rng.next_float(), rng.next_float()});
    ASSERT_TRUE(s);
    EXPECT_EQ(s->distance, kInfinity);
    EXPECT_FALSE(s->delta);
    const RGB e = escaped_radiance(l, s->wi);
    EXPECT_NEAR(s->radiance.g, e.g, 1e-4f * e.g + 1e-6f);
    if (std::abs(light_pdf(l, {}, s->wi, {}, {}) - s->pdf) > 1e-3f * s->pdf) ++mismatched;
  }
  EXPECT_LT(mismatched, 10);
}

TEST(EnvironmentLight, PowerIsTheIntegralTimesTheSceneDisk) {
  EnvironmentLight constant{RGB(0.5f)};
  constant.scene_radius = 2.0f;
  EnvironmentLight mapped{RGB(1.0f)};
  mapped.scene_radius = 2.0f;
  mapped.map = std::make_shared<const EnvironmentMap>(8, 4, std::vector<RGB>(32, RGB(0.5f)));
  EXPECT_NEAR(power(mapped), power(constant), 1e-4f * power(constant));
  EXPECT_NEAR(power(constant), kPi * 4.0f * 4.0f * kPi * 0.5f, 1e-3f);
}

// ---- the generated sky ----

TEST(Sky, SunSitsWhereItsParametersSay) {
  SkyParameters p;
  p.resolution = 256;
  p.sun_elevation = 20.0f;
  p.sun_azimuth = 90.0f;  // towards +X
  const EnvironmentMap sky = generate_sky(p);
  EXPECT_EQ(sky.width(), 256);
  EXPECT_EQ(sky.height(), 128);
  int bx = 0, by = 0;
  for (int y = 0; y < sky.height(); ++y)
    for (int x = 0; x < sky.width(); ++x)
      if (sky.pixel(x, y).luminance() > sky.pixel(bx, by).luminance()) bx = x, by = y;
  const Vec3 brightest = latlong_to_direction({(bx + 0.5f) / 256, (by + 0.5f) / 128});
  const Vec3 sun = sky_sun_direction(p);
  EXPECT_NEAR(sun.x, std::cos(radians(20.0f)), 1e-6f);
  EXPECT_GT(dot(brightest, sun), std::cos(radians(1.5f)));
  EXPECT_GT(sky.pdf(sun), 100.0f * kInv4Pi);  // importance sampling finds it
}

// The disk is normalised to the stated irradiance at any resolution: the irradiance on a plane
// facing the sun differs between resolutions only by the (smooth) sky's discretisation.
TEST(Sky, SunIrradianceDoesNotDependOnResolution) {
  SkyParameters p;
  p.sun_elevation = 35.0f;
  p.sun_angular_radius = 0.27f;
  double e[2];
  int k = 0;
  for (int res : {128, 1024}) {
    p.resolution = res;
    const EnvironmentMap sky = generate_sky(p);
    const Vec3 sun = sky_sun_direction(p);
    double sum = 0.0;
    for (int y = 0; y < sky.height(); ++y) {
      const double omega = 2.0 * M_PI / res * (std::cos(M_PI * y / sky.height()) - std::cos(M_PI * (y + 1) / sky.height()));
      for (int x = 0; x < res; ++x) {
        const Vec3 w = latlong_to_direction({(x + 0.5f) / res, (y + 0.5f) / float(sky.height())});
        sum += sky.pixel(x, y).g * omega * std::max(0.0f, dot(w, sun));
      }
    }
    e[k++] = sum;
  }
  EXPECT_GT(e[0], sky_sun_irradiance(p).g);  // sun plus sky
  EXPECT_NEAR(e[0], e[1], 0.01 * e[1]);
}

TEST(Sky, LowSunIsRedderAndRangesAreChecked) {
  SkyParameters low, high;
  low.sun_elevation = 5.0f;
  high.sun_elevation = 60.0f;
  const RGB a = sky_sun_irradiance(low), b = sky_sun_irradiance(high);
  EXPECT_GT(a.r / a.b, b.r / b.b);
  EXPECT_LT(b.g, kSkySunIrradiance);
  SkyParameters bad;
  bad.resolution = 8;
  EXPECT_THROW(generate_sky(bad), std::invalid_argument);
  bad = {};
  bad.sun_elevation = -5.0f;
  EXPECT_THROW(generate_sky(bad), std::invalid_argument);
  bad = {};
  bad.sun_angular_radius = 0.0f;
  EXPECT_THROW(generate_sky(bad), std::invalid_argument);
}

}  // namespace
}  // namespace caligo
