// Tests of blackbody.h against published and analytic values:
// - the CIE 1931 chromaticity of the Planckian locus at known temperatures (published tables,
//   e.g. Wyszecki & Stiles, "Color Science", and the CIE 1931 locus tables reproduced on
//   Wikipedia's "Planckian locus"; c2 = 1.4388e-2 m K);
// - the same chromaticity recovered from the Rec.709 colour where the locus is in gamut, which
//   checks the XYZ -> Rec.709 matrix;
// - qualitative Rec.709 colours (6500 K near white, red > green > blue when cool, blue when hot);
// - luminance 1; table interpolation against direct integration;
// - Stefan-Boltzmann: Planck's law integrated numerically over wavelength equals sigma T^4 / pi.
#include "media/blackbody.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

namespace caligo {
namespace {

struct LocusPoint {
  double kelvin, x, y;
};

// Published CIE 1931 (x, y) of the Planckian locus.
constexpr LocusPoint kLocus[] = {
    {1000, 0.6528, 0.3444}, {2000, 0.5267, 0.4133}, {3000, 0.4369, 0.4041},  {4000, 0.3805, 0.3768},
    {5000, 0.3451, 0.3516}, {6500, 0.3135, 0.3236}, {10000, 0.2807, 0.2884},
};

// The published values have 4 decimals (rounding error up to 5e-5), and a 5 nm table sum
// reproduces a 1 nm one to about 1e-5 for smooth spectra; measured differences are at most
// 1.1e-4 (at 10000 K). The brief allowed 0.002; 5e-4 is tighter and still leaves room.
constexpr double kChromaticityTolerance = 5e-4;

TEST(BlackbodyTest, XyzChromaticityMatchesPublishedPlanckianLocus) {
  for (const LocusPoint& p : kLocus) {
    const Xyz c = blackbody_xyz(p.kelvin);
    const double sum = c.x + c.y + c.z;
    EXPECT_NEAR(c.x / sum, p.x, kChromaticityTolerance) << p.kelvin << " K";
    EXPECT_NEAR(c.y / sum, p.y, kChromaticityTolerance) << p.kelvin << " K";
    EXPECT_DOUBLE_EQ(c.y, 1.0);
  }
}

// Where the locus lies inside the Rec.709 gamut (above about 1900 K) the clamp does nothing,
// so the tabulated colour converted back to XYZ must land on the published locus. This
// checks the table, its interpolation and the conversion matrices together.
TEST(BlackbodyTest, Rec709ColourConvertsBackToPublishedLocusWhereInGamut) {
  for (const LocusPoint& p : kLocus) {
    if (p.kelvin < 2000) continue;
    const RGB rgb = blackbody_color(float(p.kelvin));
    ASSERT_GT(rgb.b, 0.0f) << p.kelvin << " K should be in gamut";
    const Xyz c = rec709_to_xyz(rgb);
    const double sum = c.x + c.y + c.z;
    EXPECT_NEAR(c.x / sum, p.x, kChromaticityTolerance) << p.kelvin << " K";
    EXPECT_NEAR(c.y / sum, p.y, kChromaticityTolerance) << p.kelvin << " K";
  }
}

TEST(BlackbodyTest, MatricesAreInverses) {
  const Xyz white = rec709_to_xyz(RGB(1.0f));
  // D65: (x, y) = (0.3127, 0.3290), Y = 1.
  EXPECT_NEAR(white.x / (white.x + white.y + white.z), 0.3127, 1e-4);
  EXPECT_NEAR(white.y / (white.x + white.y + white.z), 0.3290, 1e-4);
  EXPECT_NEAR(white.y, 1.0, 1e-5);
  const RGB back = xyz_to_linear_rec709(rec709_to_xyz(RGB(0.3f, 0.7f, 0.1f)));
  EXPECT_NEAR(back.r, 0.3f, 1e-5f);
  EXPECT_NEAR(back.g, 0.7f, 1e-5f);
  EXPECT_NEAR(back.b, 0.1f, 1e-5f);
}

TEST(BlackbodyTest, ColoursHaveTheExpectedHues) {
  // 6500 K is close to (not exactly) D65, so close to white.
  const RGB d = blackbody_color(6500.0f);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(d[i], 1.0f, 0.1f) << "channel " << i;
  for (float t : {1000.0f, 1500.0f, 2000.0f, 3000.0f, 4000.0f}) {
    const RGB c = blackbody_color(t);
    EXPECT_GT(c.r, c.g) << t << " K";
    EXPECT_GT(c.g, c.b) << t << " K";
  }
  for (float t : {10000.0f, 20000.0f, 40000.0f, 1e6f}) {
    const RGB c = blackbody_color(t);
    EXPECT_GT(c.b, c.r) << t << " K";
    EXPECT_GT(c.b, c.g) << t << " K";
  }
  // Out of gamut: a 1000 K blackbody has negative blue in Rec.709, clamped to 0.
  EXPECT_EQ(blackbody_color(1000.0f).b, 0.0f);
  EXPECT_LT(xyz_to_linear_rec709(blackbody_xyz(1000.0)).b, 0.0f);
}

TEST(BlackbodyTest, LuminanceIsOneAndComponentsAreNonNegative) {
  for (float t = 100.0f; t < 1e6f; t *= 1.07f) {
    const RGB c = blackbody_color(t);
    EXPECT_NEAR(c.luminance(), 1.0f, 1e-5f) << t << " K";
    EXPECT_GE(c.r, 0.0f);
    EXPECT_GE(c.g, 0.0f);
    EXPECT_GE(c.b, 0.0f);
  }
}

TEST(BlackbodyTest, InvalidTemperaturesAreBlack) {
  EXPECT_TRUE(blackbody_color(0.0f).is_black());
  EXPECT_TRUE(blackbody_color(-300.0f).is_black());
  EXPECT_TRUE(blackbody_color(std::numeric_limits<float>::quiet_NaN()).is_black());
  EXPECT_TRUE(blackbody_color(-std::numeric_limits<float>::infinity()).is_black());
  EXPECT_EQ(blackbody_exitance_radiance(0.0f), 0.0f);
  EXPECT_EQ(blackbody_exitance_radiance(-5.0f), 0.0f);
  EXPECT_EQ(blackbody_exitance_radiance(std::numeric_limits<float>::quiet_NaN()), 0.0f);
  // +infinity is the limit 1/T -> 0 of the table (the Rayleigh-Jeans colour), finite.
  EXPECT_TRUE(blackbody_color(std::numeric_limits<float>::infinity()).is_finite());
}

TEST(BlackbodyTest, BelowTheTableIsPureRed) {
  // Below about 900 K both green and blue are negative in Rec.709, so the clamped colour is
  // pure red with luminance 1, and the table's constant extension below 500 K is exact.
  for (double t : {300.0, 499.0, 600.0, 800.0}) {
    const RGB direct = blackbody_color_direct(t);
    EXPECT_EQ(direct.g, 0.0f) << t << " K";
    EXPECT_EQ(direct.b, 0.0f) << t << " K";
    EXPECT_NEAR(blackbody_color(float(t)).r, 1.0f / 0.2126f, 1e-4f) << t << " K";
  }
}

TEST(BlackbodyTest, TableMatchesDirectIntegration) {
  // Every temperature from 300 K to 1e6 K in 0.3 % steps (lands between table nodes).
  float worst = 0.0f;
  double worst_t = 0.0;
  for (double t = 300.0; t < 1e6; t *= 1.003) {
    const RGB table = blackbody_color(float(t));
    const RGB direct = blackbody_color_direct(t);
    for (int i = 0; i < 3; ++i) {
      const float err = std::abs(table[i] - direct[i]);
      if (err > worst) worst = err, worst_t = t;
    }
  }
  EXPECT_LT(worst, 1e-3f) << "at " << worst_t << " K";
}

// Stefan-Boltzmann: integral over all wavelengths of B(lambda, T) = sigma T^4 / pi. Integrated
// in u = ln(lambda) (d lambda = lambda du) by Simpson's rule from 10 nm to 10 cm; the tails
// beyond are below 1e-9 of the total for these temperatures.
double integrate_planck(double kelvin) {
  const double u0 = std::log(1e-8), u1 = std::log(1e-1);
  const int n = 20000;  // even
  const double h = (u1 - u0) / n;
  double sum = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double lambda = std::exp(u0 + h * i);
    const double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    sum += w * planck_spectral_radiance(lambda, kelvin) * lambda;
  }
  return sum * h / 3.0;
}

TEST(BlackbodyTest, ExitanceRadianceIsPlanckIntegratedOverWavelength) {
  for (double t : {300.0, 1000.0, 1500.0, 3000.0, 6500.0, 20000.0}) {
    const double integral = integrate_planck(t);
    const double expected = blackbody_exitance_radiance(float(t));
    EXPECT_NEAR(expected / integral, 1.0, 0.005) << t << " K";
  }
  // An absolute anchor independent of our constants: the Sun's photosphere at 5772 K (IAU
  // nominal effective temperature) has exitance 6.29e7 W/m^2.
  EXPECT_NEAR(blackbody_exitance_radiance(5772.0f) * std::numbers::pi, 6.294e7, 0.005 * 6.294e7);
}

TEST(BlackbodyTest, PlanckPeakFollowsWien) {
  // Wien's displacement law: the peak of B(lambda) is at b / T, b = 2.897771955e-3 m K.
  for (double t : {1000.0, 3000.0, 6000.0}) {
    double best = 0.0, best_lambda = 0.0;
    for (double lambda = 1e-7; lambda < 1e-5; lambda *= 1.0001) {
      const double b = planck_spectral_radiance(lambda, t);
      if (b > best) best = b, best_lambda = lambda;
    }
    EXPECT_NEAR(best_lambda * t / 2.897771955e-3, 1.0, 2e-4) << t << " K";
  }
}

}  // namespace
}  // namespace caligo
