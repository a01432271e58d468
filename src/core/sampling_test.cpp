// Statistical and analytic tests of the sampling triads (sampling.h): for each warp, the pdf
// integrates to one, samples follow the pdf (chi-squared goodness of fit), and invert undoes sample.
#include "core/sampling.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <vector>

#include "core/math.h"
#include "core/rng.h"
#include "core/testing/chi_squared.h"

namespace caligo {
namespace {

// ---- Chi-squared machinery -----------------------------------------------------------------------

using test_stats::chi2_p_value;
using test_stats::chi2_survival;

// A parametrisation of a sampling domain by the unit square, used to bin samples and to integrate
// the pdf over each bin: point = from_unit(s, t), with measure element jacobian(s, t) ds dt.
template <typename Point>
struct Chart {
  std::function<Vec2(Point)> to_unit;
  std::function<Point(float s, float t)> from_unit;
  std::function<double(float s, float t)> jacobian;
};

// Directions with z in [z_lo, z_hi], parametrised by (z, phi): the solid-angle element is dz dphi.
Chart<Vec3> direction_chart(float z_lo, float z_hi) {
  return {[=](Vec3 w) {
            float phi = std::atan2(w.y, w.x);
            if (phi < 0.0f) phi += 2.0f * kPi;
            return Vec2{(w.z - z_lo) / (z_hi - z_lo), phi * kInv2Pi};
          },
          [=](float s, float t) {
            const float z = z_lo + s * (z_hi - z_lo);
            return spherical_direction(safe_sqrt(1.0f - z * z), z, 2.0f * kPi * t);
          },
          [=](float, float) { return double(z_hi - z_lo) * 2.0 * kPi; }};
}

// The unit disk in polar coordinates (r, phi): area element r dr dphi.
Chart<Vec2> disk_chart() {
  return {[](Vec2 p) {
            float phi = std::atan2(p.y, p.x);
            if (phi < 0.0f) phi += 2.0f * kPi;
            return Vec2{std::hypot(p.x, p.y), phi * kInv2Pi};
          },
          [](float s, float t) {
            return Vec2{s * std::cos(2.0f * kPi * t), s * std::sin(2.0f * kPi * t)};
          },
          [](float s, float) { return double(s) * 2.0 * kPi; }};
}

// Barycentrics (b0, b1) = (s, t (1 - s)): a parametrisation unrelated to the warp under test.
Chart<Vec3> triangle_chart() {
  return {[](Vec3 b) {
            return Vec2{b.x, b.x < 1.0f ? b.y / (1.0f - b.x) : 0.0f};
          },
          [](float s, float t) { return Vec3(s, t * (1.0f - s), (1.0f - s) * (1.0f - t)); },
          [](float s, float) { return double(1.0f - s); }};
}

constexpr int kBins = 16;         // per chart axis
constexpr int kSubdivisions = 8;  // midpoint-rule cells per bin and axis
constexpr int kSamples = 100000;

// Integrates pdf over each bin of the chart and scales to expected sample counts.
template <typename Point>
std::vector<double> expected_counts(const Chart<Point>& chart, const std::function<double(Point)>& pdf) {
  std::vector<double> expected(kBins * kBins, 0.0);
  const double h = 1.0 / (kBins * kSubdivisions);
  for (int i = 0; i < kBins * kSubdivisions; ++i)
    for (int j = 0; j < kBins * kSubdivisions; ++j) {
      const float s = float((i + 0.5) * h), t = float((j + 0.5) * h);
      const double mass = pdf(chart.from_unit(s, t)) * chart.jacobian(s, t) * h * h;
      expected[size_t((i / kSubdivisions) * kBins + j / kSubdivisions)] += mass * kSamples;
    }
  return expected;
}

template <typename Point>
std::vector<double> observed_counts(const Chart<Point>& chart, const std::function<Point(Vec2)>& sample) {
  std::vector<double> observed(kBins * kBins, 0.0);
  Pcg32 rng(7, 11);
  for (int n = 0; n < kSamples; ++n) {
    const float u0 = rng.next_float(), u1 = rng.next_float();
    const Vec2 st = chart.to_unit(sample({u0, u1}));
    const int i = std::clamp(int(st.x * kBins), 0, kBins - 1),
              j = std::clamp(int(st.y * kBins), 0, kBins - 1);
    observed[size_t(i * kBins + j)] += 1.0;
  }
  return observed;
}

template <typename Point>
double sample_pdf_p_value(const Chart<Point>& chart, const std::function<Point(Vec2)>& sample,
                          const std::function<double(Point)>& pdf) {
  return chi2_p_value(observed_counts(chart, sample), expected_counts(chart, pdf));
}

constexpr double kMinPValue = 1e-3;

// ---- Normalisation quadrature --------------------------------------------------------------------

// Integral of a direction pdf over the whole sphere, midpoint rule in (theta, phi).
double integrate_over_sphere(const std::function<double(Vec3)>& pdf) {
  // Fine in theta so that the narrowest cone tested (0.045 rad) spans hundreds of cells.
  const int n_theta = 16384, n_phi = 16;
  const double d_theta = kPi / n_theta, d_phi = 2.0 * kPi / n_phi;
  double sum = 0.0;
  for (int i = 0; i < n_theta; ++i) {
    const double theta = (i + 0.5) * d_theta;
    for (int j = 0; j < n_phi; ++j) {
      const Vec3 w =
          spherical_direction(float(std::sin(theta)), float(std::cos(theta)), float((j + 0.5) * d_phi));
      sum += pdf(w) * std::sin(theta) * d_theta * d_phi;
    }
  }
  return sum;
}

// Integral of a planar pdf over [-1, 1]^2, midpoint rule on a Cartesian grid.
double integrate_over_square(const std::function<double(Vec2)>& pdf) {
  const int n = 2048;
  const double h = 2.0 / n;
  double sum = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      sum += pdf({float(-1.0 + (i + 0.5) * h), float(-1.0 + (j + 0.5) * h)}) * h * h;
  return sum;
}

constexpr double kNormalisationTolerance = 0.01;

// ---- Round trips ---------------------------------------------------------------------------------

constexpr int kRoundTrips = 20000;
constexpr float kRoundTripTolerance = 1e-4f;

template <typename Point>
void expect_round_trip(const std::function<Point(Vec2)>& sample, const std::function<Vec2(Point)>& invert) {
  Pcg32 rng(3, 5);
  for (int n = 0; n < kRoundTrips; ++n) {
    const Vec2 u{rng.next_float(), rng.next_float()};
    const Vec2 back = invert(sample(u));
    ASSERT_NEAR(back.x, u.x, kRoundTripTolerance) << "u = (" << u.x << ", " << u.y << ")";
    ASSERT_NEAR(back.y, u.y, kRoundTripTolerance) << "u = (" << u.x << ", " << u.y << ")";
    ASSERT_GE(back.x, 0.0f);
    ASSERT_LT(back.x, 1.0f);
    ASSERT_GE(back.y, 0.0f);
    ASSERT_LT(back.y, 1.0f);
  }
}

// Pdfs as functions of a point of the whole domain, zero outside their support.
double disk_pdf_at(Vec2 p) { return p.x * p.x + p.y * p.y < 1.0f ? uniform_disk_pdf() : 0.0; }
double sphere_pdf_at(Vec3) { return uniform_sphere_pdf(); }
double hemisphere_pdf_at(Vec3 w) { return w.z >= 0.0f ? uniform_hemisphere_pdf() : 0.0; }
double cosine_pdf_at(Vec3 w) { return cosine_hemisphere_pdf(w.z); }
std::function<double(Vec3)> cone_pdf_at(float cos_max) {
  return [=](Vec3 w) { return w.z >= cos_max ? uniform_cone_pdf(cos_max) : 0.0; };
}

const float kConeCosines[] = {-0.5f, 0.3f, 0.9f, 0.999f};

}  // namespace

// ---- The chi-squared machinery itself ------------------------------------------------------------

TEST(Chi2, SurvivalMatchesTables) {
  // 95th percentiles of the chi-squared distribution.
  EXPECT_NEAR(chi2_survival(3.841, 1), 0.05, 1e-4);
  EXPECT_NEAR(chi2_survival(18.307, 10), 0.05, 1e-4);
  EXPECT_NEAR(chi2_survival(124.342, 100), 0.05, 1e-4);
  EXPECT_NEAR(chi2_survival(2.0, 2), std::exp(-1.0), 1e-10);  // two dof: exp(-x / 2)
  EXPECT_NEAR(chi2_survival(0.0, 5), 1.0, 1e-12);
}

TEST(Chi2, DetectsWrongPdf) {
  // Uniform hemisphere samples tested against the cosine pdf must fail decisively.
  const double p =
      sample_pdf_p_value<Vec3>(direction_chart(0.0f, 1.0f), sample_uniform_hemisphere, cosine_pdf_at);
  EXPECT_LT(p, 1e-9);
  // So must a pdf that is right in shape but wrongly normalised (a cone tested as a hemisphere).
  const double p_cone = sample_pdf_p_value<Vec3>(
      direction_chart(0.0f, 1.0f), [](Vec2 u) { return sample_uniform_cone(u, 0.1f); }, hemisphere_pdf_at);
  EXPECT_LT(p_cone, 1e-9);
}

// ---- Disk ----------------------------------------------------------------------------------------

TEST(DiskConcentric, PdfIntegratesToOne) {
  EXPECT_NEAR(integrate_over_square(disk_pdf_at), 1.0, kNormalisationTolerance);
}

TEST(DiskConcentric, SamplesFollowPdf) {
  EXPECT_GT(sample_pdf_p_value<Vec2>(disk_chart(), sample_uniform_disk_concentric, disk_pdf_at), kMinPValue);
}

TEST(DiskConcentric, InvertRoundTrip) {
  expect_round_trip<Vec2>(sample_uniform_disk_concentric, invert_uniform_disk_concentric);
  const Vec2 centre = invert_uniform_disk_concentric({0.0f, 0.0f});
  EXPECT_FLOAT_EQ(centre.x, 0.5f);
  EXPECT_FLOAT_EQ(centre.y, 0.5f);
}

// ---- Sphere --------------------------------------------------------------------------------------

TEST(UniformSphere, PdfIntegratesToOne) {
  EXPECT_NEAR(integrate_over_sphere(sphere_pdf_at), 1.0, kNormalisationTolerance);
}

TEST(UniformSphere, SamplesFollowPdf) {
  EXPECT_GT(sample_pdf_p_value<Vec3>(direction_chart(-1.0f, 1.0f), sample_uniform_sphere, sphere_pdf_at),
            kMinPValue);
}

TEST(UniformSphere, InvertRoundTrip) {
  expect_round_trip<Vec3>(sample_uniform_sphere, invert_uniform_sphere);
}

TEST(UniformSphere, SamplesAreUnitVectors) {
  Pcg32 rng;
  for (int n = 0; n < 1000; ++n)
    EXPECT_NEAR(length(sample_uniform_sphere({rng.next_float(), rng.next_float()})), 1.0f, 1e-5f);
}

// ---- Hemisphere ----------------------------------------------------------------------------------

TEST(UniformHemisphere, PdfIntegratesToOne) {
  EXPECT_NEAR(integrate_over_sphere(hemisphere_pdf_at), 1.0, kNormalisationTolerance);
}

TEST(UniformHemisphere, SamplesFollowPdf) {
  EXPECT_GT(
      sample_pdf_p_value<Vec3>(direction_chart(0.0f, 1.0f), sample_uniform_hemisphere, hemisphere_pdf_at),
      kMinPValue);
}

TEST(UniformHemisphere, InvertRoundTrip) {
  expect_round_trip<Vec3>(sample_uniform_hemisphere, invert_uniform_hemisphere);
}

// ---- Cosine hemisphere ---------------------------------------------------------------------------

TEST(CosineHemisphere, PdfIntegratesToOne) {
  EXPECT_NEAR(integrate_over_sphere(cosine_pdf_at), 1.0, kNormalisationTolerance);
}

TEST(CosineHemisphere, SamplesFollowPdf) {
  EXPECT_GT(sample_pdf_p_value<Vec3>(direction_chart(0.0f, 1.0f), sample_cosine_hemisphere, cosine_pdf_at),
            kMinPValue);
}

TEST(CosineHemisphere, InvertRoundTrip) {
  expect_round_trip<Vec3>(sample_cosine_hemisphere, invert_cosine_hemisphere);
}

TEST(CosineHemisphere, PdfIsZeroBelowHorizon) {
  EXPECT_EQ(cosine_hemisphere_pdf(-0.5f), 0.0f);
  EXPECT_FLOAT_EQ(cosine_hemisphere_pdf(1.0f), kInvPi);
}

// ---- Cone ----------------------------------------------------------------------------------------

TEST(UniformCone, PdfIntegratesToOne) {
  for (float cos_max : kConeCosines)
    EXPECT_NEAR(integrate_over_sphere(cone_pdf_at(cos_max)), 1.0, kNormalisationTolerance) << cos_max;
}

TEST(UniformCone, SamplesFollowPdf) {
  for (float cos_max : kConeCosines) {
    const auto sample = [=](Vec2 u) { return sample_uniform_cone(u, cos_max); };
    EXPECT_GT(sample_pdf_p_value<Vec3>(direction_chart(cos_max, 1.0f), sample, cone_pdf_at(cos_max)),
              kMinPValue)
        << cos_max;
  }
}

TEST(UniformCone, InvertRoundTrip) {
  for (float cos_max : kConeCosines) {
    SCOPED_TRACE(cos_max);
    expect_round_trip<Vec3>([=](Vec2 u) { return sample_uniform_cone(u, cos_max); },
                            [=](Vec3 w) { return invert_uniform_cone(w, cos_max); });
  }
}

TEST(UniformCone, StaysInsideCone) {
  Pcg32 rng;
  for (int n = 0; n < 1000; ++n) {
    const Vec3 w = sample_uniform_cone({rng.next_float(), rng.next_float()}, 0.8f);
    EXPECT_GE(w.z, 0.8f - 1e-6f);
    EXPECT_NEAR(length(w), 1.0f, 1e-5f);
  }
}

// ---- Triangle ------------------------------------------------------------------------------------

// The pdf w.r.t. area is 1 / area exactly when the warp's Jacobian determinant is constant and
// equal to the area of the barycentric triangle (1/2): then it integrates to one.
TEST(UniformTriangle, JacobianIsConstantSoPdfIntegratesToOne) {
  Pcg32 rng(1, 2);
  const float h = 1e-3f;
  for (int n = 0; n < 2000; ++n) {
    const Vec2 u{h + rng.next_float() * (1.0f - 2.0f * h), h + rng.next_float() * (1.0f - 2.0f * h)};
    if (std::abs(u.x - u.y) < 2.0f * h) continue;  // the map has a kink on the diagonal
    const Vec3 dx = sample_uniform_triangle({u.x + h, u.y}) - sample_uniform_triangle({u.x - h, u.y});
    const Vec3 dy = sample_uniform_triangle({u.x, u.y + h}) - sample_uniform_triangle({u.x, u.y - h});
    const float det = (dx.x * dy.y - dx.y * dy.x) / (4.0f * h * h);
    EXPECT_NEAR(std::abs(det), 0.5f, 1e-3f);
  }
}

TEST(UniformTriangle, SamplesFollowPdf) {
  // Density 2 w.r.t. (b0, b1): the barycentric triangle has area 1/2.
  const auto pdf = [](Vec3 b) { return b.x >= 0.0f && b.y >= 0.0f && b.x + b.y <= 1.0f ? 2.0 : 0.0; };
  EXPECT_GT(sample_pdf_p_value<Vec3>(triangle_chart(), sample_uniform_triangle, pdf), kMinPValue);
}

TEST(UniformTriangle, InvertRoundTrip) {
  expect_round_trip<Vec3>(sample_uniform_triangle, invert_uniform_triangle);
}

TEST(UniformTriangle, BarycentricsAreValid) {
  Pcg32 rng;
  for (int n = 0; n < 1000; ++n) {
    const Vec3 b = sample_uniform_triangle({rng.next_float(), rng.next_float()});
    EXPECT_GE(b.x, 0.0f);
    EXPECT_GE(b.y, 0.0f);
    EXPECT_GE(b.z, -1e-6f);
    EXPECT_NEAR(b.x + b.y + b.z, 1.0f, 1e-6f);
  }
}

// ---- Discrete distribution -----------------------------------------------------------------------

TEST(DiscreteDistribution, RejectsInvalidWeights) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<std::vector<float>> bad = {
      {}, {0.0f, 0.0f}, {1.0f, -1.0f}, {1.0f, nan}, {kInfinity, 1.0f}};
  for (const auto& w : bad) EXPECT_THROW(DiscreteDistribution{w}, std::invalid_argument);
}

TEST(DiscreteDistribution, PmfAndTotal) {
  const std::vector<float> w = {1.0f, 0.0f, 3.0f, 4.0f};
  const DiscreteDistribution d(w);
  EXPECT_EQ(d.size(), 4u);
  EXPECT_FALSE(d.empty());
  EXPECT_FLOAT_EQ(d.total(), 8.0f);
  for (int i = 0; i < 4; ++i) EXPECT_FLOAT_EQ(d.pmf(i), w[size_t(i)] / 8.0f);
  EXPECT_TRUE(DiscreteDistribution().empty());
}

TEST(DiscreteDistribution, FrequenciesMatchPmf) {
  const std::vector<float> w = {1.0f, 0.0f, 3.0f, 2.0f, 0.0f, 4.0f, 0.5f, 0.0f};
  const DiscreteDistribution d(w);
  std::vector<double> observed(w.size(), 0.0), expected(w.size(), 0.0);
  Pcg32 rng(5, 9);
  for (int n = 0; n < kSamples; ++n) {
    float pmf = -1.0f;
    const int i = d.sample(rng.next_float(), &pmf);
    ASSERT_GT(w[size_t(i)], 0.0f) << "zero-weight entry " << i << " chosen";
    ASSERT_EQ(pmf, d.pmf(i));
    observed[size_t(i)] += 1.0;
  }
  for (size_t i = 0; i < w.size(); ++i) expected[i] = double(d.pmf(int(i))) * kSamples;
  EXPECT_GT(chi2_p_value(observed, expected), kMinPValue);
}

TEST(DiscreteDistribution, ZeroWeightsNeverChosenAtBucketEdges) {
  const std::vector<float> w = {0.0f, 2.0f, 0.0f, 0.0f, 1.0f, 0.0f};
  const DiscreteDistribution d(w);
  EXPECT_EQ(d.sample(0.0f), 1);
  EXPECT_EQ(d.sample(kOneMinusEpsilon), 4);
  EXPECT_EQ(d.sample(1.0f), 4);  // out-of-range u is clamped
  for (int i = 0; i <= int(w.size()); ++i) {
    const float edge = i < int(w.size()) ? d.invert(i) : 1.0f;
    EXPECT_GT(w[size_t(d.sample(std::min(edge, kOneMinusEpsilon)))], 0.0f);
    if (edge > 0.0f) {
      EXPECT_GT(w[size_t(d.sample(std::nextafter(edge, 0.0f)))], 0.0f);
    }
  }
}

TEST(DiscreteDistribution, InvertGivesBucketStart) {
  const std::vector<float> w = {1.0f, 3.0f, 0.0f, 4.0f};
  const DiscreteDistribution d(w);
  const float starts[] = {0.0f, 0.125f, 0.5f, 0.5f};
  for (int i = 0; i < 4; ++i) EXPECT_FLOAT_EQ(d.invert(i), starts[i]);
  for (int i : {0, 1, 3}) {
    EXPECT_EQ(d.sample(d.invert(i)), i);
    const float end = i + 1 < 4 ? d.invert(i + 1) : 1.0f;
    EXPECT_EQ(d.sample(std::nextafter(end, 0.0f)), i);  // the last u of the bucket
  }
}

TEST(DiscreteDistribution, RemappedSampleIsUniform) {
  const std::vector<float> w = {1.0f, 0.0f, 3.0f, 2.0f, 7.0f};
  const DiscreteDistribution d(w);
  constexpr int kRemapBins = 64;
  std::vector<double> observed(kRemapBins, 0.0), expected(kRemapBins, double(kSamples) / kRemapBins);
  Pcg32 rng(13, 17);
  for (int n = 0; n < kSamples; ++n) {
    const float u = rng.next_float();
    float remapped = -1.0f;
    const int i = d.sample(u, nullptr, &remapped);
    ASSERT_GE(remapped, 0.0f);
    ASSERT_LT(remapped, 1.0f);
    // The remapped value is u's position inside the chosen bucket.
    const float end = i + 1 < int(w.size()) ? d.invert(i + 1) : 1.0f;
    ASSERT_NEAR(d.invert(i) + remapped * (end - d.invert(i)), u, 1e-5f);
    observed[size_t(remapped * kRemapBins)] += 1.0;
  }
  EXPECT_GT(chi2_p_value(observed, expected), kMinPValue);
}

TEST(DiscreteDistribution, SingleWeight) {
  const std::vector<float> w = {0.25f};
  const DiscreteDistribution d(w);
  float pmf = 0.0f, remapped = -1.0f;
  EXPECT_EQ(d.sample(0.3f, &pmf, &remapped), 0);
  EXPECT_EQ(pmf, 1.0f);
  EXPECT_FLOAT_EQ(remapped, 0.3f);
}

// ---- MIS heuristics ------------------------------------------------------------------------------

TEST(MisHeuristics, PowerHeuristicValues) {
  EXPECT_FLOAT_EQ(power_heuristic(1, 1.0f, 1, 1.0f), 0.5f);
  EXPECT_FLOAT_EQ(power_heuristic(1, 2.0f, 1, 1.0f), 0.8f);
  EXPECT_FLOAT_EQ(power_heuristic(2, 1.0f, 1, 1.0f), 0.8f);
  EXPECT_FLOAT_EQ(power_heuristic(1, 1.0f, 1, 3.0f), 0.1f);
  EXPECT_EQ(power_heuristic(1, kInfinity, 1, 5.0f), 1.0f);  // delta strategy takes all
  EXPECT_EQ(power_heuristic(1, kInfinity, 1, kInfinity), 1.0f);
  EXPECT_EQ(power_heuristic(1, 1.0f, 1, kInfinity), 0.0f);
  EXPECT_EQ(power_heuristic(1, 0.0f, 1, 0.0f), 0.0f);
  EXPECT_EQ(power_heuristic(1, 0.0f, 1, 2.0f), 0.0f);
  EXPECT_FLOAT_EQ(power_heuristic(1, 1e30f, 1, 1e30f), 0.5f);  // squares would overflow
}

TEST(MisHeuristics, BalanceHeuristicValues) {
  EXPECT_FLOAT_EQ(balance_heuristic(1, 1.0f, 1, 1.0f), 0.5f);
  EXPECT_FLOAT_EQ(balance_heuristic(1, 2.0f, 1, 1.0f), 2.0f / 3.0f);
  EXPECT_FLOAT_EQ(balance_heuristic(1, 1.0f, 3, 1.0f), 0.25f);
  EXPECT_EQ(balance_heuristic(1, kInfinity, 1, 5.0f), 1.0f);
  EXPECT_EQ(balance_heuristic(1, 0.0f, 1, 0.0f), 0.0f);
}

TEST(MisHeuristics, WeightsOfTwoStrategiesSumToOne) {
  Pcg32 rng;
  for (int n = 0; n < 1000; ++n) {
    const float f = rng.next_float() * 10.0f + 1e-3f, g = rng.next_float() * 10.0f + 1e-3f;
    EXPECT_NEAR(power_heuristic(1, f, 1, g) + power_heuristic(1, g, 1, f), 1.0f, 1e-5f);
    EXPECT_NEAR(balance_heuristic(1, f, 1, g) + balance_heuristic(1, g, 1, f), 1.0f, 1e-5f);
  }
}

}  // namespace caligo
