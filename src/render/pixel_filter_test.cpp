#include "render/pixel_filter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/rng.h"
#include "core/testing/chi_squared.h"

namespace caligo {
namespace {

using test_stats::chi2_p_value;

std::vector<PixelFilter> every_filter() {
  return {PixelFilter::box(), PixelFilter::box(1.0f), PixelFilter::gaussian(), PixelFilter::gaussian(2.0f, 0.8f),
          PixelFilter::blackman_harris(), PixelFilter::blackman_harris(1.5f)};
}

// Integral of the analytic filter over [a, b] (composite Simpson, 2000 intervals).
double integral_1d(const PixelFilter& f, double a, double b) {
  const int n = 2000;
  const double h = (b - a) / n;
  double s = f.evaluate_1d(float(a)) + f.evaluate_1d(float(b));
  for (int k = 1; k < n; ++k) s += (k % 2 ? 4.0 : 2.0) * f.evaluate_1d(float(a + k * h));
  return s * h / 3.0;
}

TEST(PixelFilter, TabulatedDensityIntegratesToOne) {
  for (const PixelFilter& f : every_filter()) {
    // Midpoint rule on a grid finer than the table: exact for a piecewise-constant density.
    const int n = 8 * PixelFilter::kTableSize;
    const double r = f.radius(), dx = 2.0 * r / n;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) sum += f.pdf_1d(float(-r + (i + 0.5) * dx)) * dx;
    EXPECT_NEAR(sum, 1.0, 1e-5) << pixel_filter_name(f.type()) << " r=" << r;
    EXPECT_EQ(f.pdf_1d(float(r) * 1.01f), 0.0f);
    // 2D: the product density over a 256^2 grid.
    const int m = 256;
    const double d = 2.0 * r / m;
    double sum2 = 0.0;
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) sum2 += f.pdf({float(-r + (i + 0.5) * d), float(-r + (j + 0.5) * d)}) * d * d;
    EXPECT_NEAR(sum2, 1.0, 2e-3) << pixel_filter_name(f.type());
  }
}

// The tabulated density is the normalised filter up to the table's resolution: at bin
// centres, bin average and value differ by f'' dx^2 / 24 (~1e-6 of the peak here).
TEST(PixelFilter, DensityIsTheNormalisedFilter) {
  for (const PixelFilter& f : every_filter()) {
    const double r = f.radius(), total = integral_1d(f, -r, r);
    const double peak = f.evaluate_1d(0.0f) / total;
    const double dx = 2.0 * r / PixelFilter::kTableSize;
    for (int i = 0; i < PixelFilter::kTableSize; i += 7) {
      const double x = -r + (i + 0.5) * dx;
      EXPECT_NEAR(f.pdf_1d(float(x)), f.evaluate_1d(float(x)) / total, 1e-4 * peak)
          << pixel_filter_name(f.type()) << " x=" << x;
    }
  }
}

// Pearson's chi-squared test of 200,000 sampled 2D offsets in 16 x 16 bins over [-r, r]^2
// against the masses of the normalised analytic filter (separable: products of 1D integrals).
double sampled_offsets_p_value(const PixelFilter& sampled, const PixelFilter& reference) {
  constexpr int kBins = 16, kSamples = 200'000;
  const double r = reference.radius(), w = 2.0 * r / kBins, total = integral_1d(reference, -r, r);
  std::vector<double> mass(kBins);
  for (int i = 0; i < kBins; ++i) mass[size_t(i)] = integral_1d(reference, -r + i * w, -r + (i + 1) * w) / total;
  std::vector<double> expected(kBins * kBins), observed(kBins * kBins, 0.0);
  for (int j = 0; j < kBins; ++j)
    for (int i = 0; i < kBins; ++i) expected[size_t(j * kBins + i)] = kSamples * mass[size_t(i)] * mass[size_t(j)];
  Pcg32 rng(5, 11);
  for (int n = 0; n < kSamples; ++n) {
    const Vec2 o = sampled.sample_offset({rng.next_float(), rng.next_float()});
    EXPECT_TRUE(std::abs(o.x) <= sampled.radius() && std::abs(o.y) <= sampled.radius());
    const int i = std::clamp(int((o.x + r) / w), 0, kBins - 1), j = std::clamp(int((o.y + r) / w), 0, kBins - 1);
    observed[size_t(j * kBins + i)] += 1.0;
  }
  return chi2_p_value(observed, expected);
}

TEST(PixelFilter, SampledOffsetsFollowTheFilter) {
  for (const PixelFilter& f : every_filter())
    EXPECT_GT(sampled_offsets_p_value(f, f), 1e-3) << pixel_filter_name(f.type()) << " r=" << f.radius();
}

// The test has power: a Gaussian of the same radius does not pass for Blackman-Harris.
TEST(PixelFilter, ChiSquaredTellsFiltersApart) {
  EXPECT_LT(sampled_offsets_p_value(PixelFilter::gaussian(1.5f, 0.5f), PixelFilter::blackman_harris(1.5f)), 1e-6);
}

TEST(PixelFilter, BoxOfHalfAPixelIsTheUniformJitter) {
  const PixelFilter box;  // the default: box, radius 0.5
  EXPECT_EQ(box.type(), PixelFilterType::box);
  for (float u : {0.0f, 0.25f, 0.5f, 0.75f, 0.999f}) EXPECT_NEAR(box.sample_1d(u), u - 0.5f, 1e-7f);
  EXPECT_FLOAT_EQ(box.pdf({0.1f, -0.3f}), 1.0f);
}

TEST(PixelFilter, SamplingInvertsTheCdfMonotonically) {
  const PixelFilter f = PixelFilter::gaussian();
  float previous = -f.radius();
  for (int i = 0; i <= 1000; ++i) {
    const float x = f.sample_1d(std::min(float(i) / 1000.0f, 0x1.fffffep-1f));
    EXPECT_GE(x, previous);
    previous = x;
  }
  EXPECT_NEAR(f.sample_1d(0.5f), 0.0f, 1e-5f);  // symmetric filter: the median is the centre
}

TEST(PixelFilter, RejectsBadParameters) {
  EXPECT_THROW(PixelFilter::box(0.0f), std::invalid_argument);
  EXPECT_THROW(PixelFilter::gaussian(1.5f, -1.0f), std::invalid_argument);
  EXPECT_THROW(PixelFilter::blackman_harris(std::nanf("")), std::invalid_argument);
  EXPECT_THROW(PixelFilter::blackman_harris(17.0f), std::invalid_argument);
}

TEST(PixelFilter, Names) {
  for (PixelFilterType t : {PixelFilterType::box, PixelFilterType::gaussian, PixelFilterType::blackman_harris})
    EXPECT_EQ(pixel_filter_type_from_name(pixel_filter_name(t)), t);
  EXPECT_EQ(pixel_filter_type_from_name("blackman-harris"), PixelFilterType::blackman_harris);
  EXPECT_FALSE(pixel_filter_type_from_name("mitchell"));
}

}  // namespace
}  // namespace caligo
