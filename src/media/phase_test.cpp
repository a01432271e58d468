// Statistical and analytic tests of the phase functions (phase.h): for every member of the
// closed set and a spread of parameters, the function integrates to one over the sphere,
// samples follow it (chi-squared goodness of fit in theta, and jointly in theta and azimuth),
// the returned pdf is phase_eval, the mean cosine matches both the samples and a quadrature,
// and the value depends on cos_theta only.
#include "media/phase.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "core/math.h"
#include "core/rng.h"
#include "core/testing/chi_squared.h"

namespace caligo {
namespace {

// ---- Chi-squared machinery (as in core/sampling_test.cpp) ----------------------------------------

using test_stats::chi2_p_value;
using test_stats::chi2_survival;

constexpr double kMinPValue = 1e-3;
constexpr int kSamples = 50000;

// ---- The phase functions under test --------------------------------------------------------------

struct Case {
  std::string name;
  PhaseFunction phase;
};

std::vector<Case> all_cases() {
  std::vector<Case> cases = {{"isotropic", IsotropicPhase{}}};
  for (float g : {-0.95f, -0.9f, -0.3f, 0.0f, 1e-4f, 0.5f, 0.8f, 0.95f}) {
    std::ostringstream name;
    name << "HG g=" << g;
    cases.push_back({name.str(), HenyeyGreensteinPhase{g}});
  }
  for (float k : {-0.9f, -0.3f, 0.0f, 0.5f, SchlickPhase::from_g(0.8f).k, 0.95f}) {
    std::ostringstream name;
    name << "Schlick k=" << k;
    cases.push_back({name.str(), SchlickPhase{k}});
  }
  const DoubleHenyeyGreensteinPhase doubles[] = {{0.5f, -0.3f, 0.7f},
                                                 {0.95f, -0.9f, 0.5f},
                                                 {0.8f, 0.2f, 0.1f},
                                                 {0.9f, -0.5f, 0.0f},
                                                 {0.9f, -0.5f, 1.0f}};
  for (const auto& d : doubles) {
    std::ostringstream name;
    name << "double HG g1=" << d.g1 << " g2=" << d.g2 << " w=" << d.w;
    cases.push_back({name.str(), d});
  }
  return cases;
}

// A travel direction in no special position relative to the frame construction.
Vec3 generic_wo() { return normalize(Vec3(0.3f, -0.5f, 0.8f)); }

// ---- Quadrature in theta -------------------------------------------------------------------------

// Midpoint cells in theta over [0, pi]: fine enough that the g = 0.95 lobe (half width about
// 0.05 rad) spans hundreds of cells. Each cell's mass is 2 pi p(theta_mid) (cos theta_0 - cos theta_1),
// evaluated through phase_eval at a varying azimuth about wo.
constexpr int kCells = 20000;
constexpr double kCellWidth = std::numbers::pi / kCells;

std::vector<double> cell_masses(const PhaseFunction& phase, Vec3 wo) {
  const Frame frame = Frame::from_z(wo);
  std::vector<double> mass(kCells);
  for (int i = 0; i < kCells; ++i) {
    const double theta = (i + 0.5) * kCellWidth,
                 phi = 2.0 * std::numbers::pi * std::fmod(i * 0.6180339887, 1.0);
    const Vec3 wi =
        frame.to_world(spherical_direction(float(std::sin(theta)), float(std::cos(theta)), float(phi)));
    mass[size_t(i)] = 2.0 * std::numbers::pi * phase_eval(phase, wo, wi) *
                      (std::cos(i * kCellWidth) - std::cos((i + 1) * kCellWidth));
  }
  return mass;
}

// The most accurate table: with wo = +z, dot(wo, wi) is exactly wi.z, so no rounding of the
// cosine perturbs the peak of a sharp lobe.
std::vector<double> reference_masses(const PhaseFunction& phase) { return cell_masses(phase, Vec3(0, 0, 1)); }

double total(const std::vector<double>& v) {
  double sum = 0.0;
  for (double x : v) sum += x;
  return sum;
}

// Groups the cells into `bins` runs of roughly equal probability; returns each cell's bin.
std::vector<int> equal_probability_bins(const std::vector<double>& mass, int bins) {
  std::vector<int> bin_of_cell(mass.size());
  double before = 0.0;
  for (size_t i = 0; i < mass.size(); ++i) {
    bin_of_cell[i] = std::min(bins - 1, int((before + 0.5 * mass[i]) * bins));
    before += mass[i];
  }
  return bin_of_cell;
}

// Polar angle and azimuth of wi in the frame about wo, accurate near the poles.
struct Polar {
  double theta, phi;
};
Polar polar_about(Vec3 wo, Vec3 wi) {
  const Vec3 l = Frame::from_z(wo).to_local(wi);
  const double phi = std::atan2(double(l.y), double(l.x));
  return {std::atan2(std::hypot(double(l.x), double(l.y)), double(l.z)),
          phi < 0.0 ? phi + 2.0 * std::numbers::pi : phi};
}

int cell_of(double theta) { return std::clamp(int(theta / kCellWidth), 0, kCells - 1); }

// Chi-squared p-value of `sampled`'s directions against the theta distribution of `reference`,
// over `theta_bins` equal-probability bins of theta times `phi_bins` uniform bins of azimuth.
double p_value(const PhaseFunction& sampled, const PhaseFunction& reference, int theta_bins, int phi_bins) {
  const std::vector<double> mass = reference_masses(reference);
  const std::vector<int> bin_of_cell = equal_probability_bins(mass, theta_bins);
  std::vector<double> expected(size_t(theta_bins * phi_bins), 0.0), observed(expected.size(), 0.0);
  for (size_t i = 0; i < mass.size(); ++i)
    for (int j = 0; j < phi_bins; ++j)
      expected[size_t(bin_of_cell[i] * phi_bins + j)] += mass[i] * kSamples / phi_bins;
  const Vec3 wo = generic_wo();
  Pcg32 rng(17, 23);
  for (int n = 0; n < kSamples; ++n) {
    const PhaseSample s = phase_sample(sampled, wo, {rng.next_float(), rng.next_float()});
    const Polar p = polar_about(wo, s.wi);
    const int j = std::min(phi_bins - 1, int(p.phi / (2.0 * std::numbers::pi) * phi_bins));
    observed[size_t(bin_of_cell[size_t(cell_of(p.theta))] * phi_bins + j)] += 1.0;
  }
  return chi2_p_value(observed, expected);
}

double mean_cosine_by_quadrature(const PhaseFunction& phase) {
  const std::vector<double> mass = reference_masses(phase);
  double sum = 0.0;
  for (int i = 0; i < kCells; ++i) sum += std::cos((i + 0.5) * kCellWidth) * mass[size_t(i)];
  return sum;
}

}  // namespace

// ---- Normalisation -------------------------------------------------------------------------------

TEST(Phase, IntegratesToOneOverTheSphere) {
  for (const Case& c : all_cases()) {
    SCOPED_TRACE(c.name);
    EXPECT_NEAR(total(reference_masses(c.phase)), 1.0, 1e-3);
    EXPECT_NEAR(total(cell_masses(c.phase, generic_wo())), 1.0, 1e-3);
  }
}

// ---- Sampling ------------------------------------------------------------------------------------

TEST(Phase, PdfIsPhaseEvalAtTheSampledDirection) {
  const Vec3 wos[] = {generic_wo(), Vec3(0, 0, 1), Vec3(0, 0, -1), Vec3(1, 0, 0),
                      normalize(Vec3(-1, 1e-4f, -1e-3f))};
  for (const Case& c : all_cases()) {
    SCOPED_TRACE(c.name);
    Pcg32 rng(1, 2);
    for (Vec3 wo : wos)
      for (int n = 0; n < 2000; ++n) {
        const PhaseSample s = phase_sample(c.phase, wo, {rng.next_float(), rng.next_float()});
        ASSERT_NEAR(length(s.wi), 1.0f, 1e-5f);
        ASSERT_TRUE(std::isfinite(s.pdf));
        ASSERT_GT(s.pdf, 0.0f);
        ASSERT_EQ(s.pdf, phase_eval(c.phase, wo, s.wi));
        ASSERT_EQ(s.pdf, phase_pdf(c.phase, wo, s.wi));
      }
  }
}

TEST(Phase, ExtremeRandomNumbersGiveValidDirections) {
  const float us[] = {0.0f, 1e-7f, 0.5f, 1.0f - 1e-7f, kOneMinusEpsilon};
  for (const Case& c : all_cases()) {
    SCOPED_TRACE(c.name);
    for (float u0 : us)
      for (float u1 : us) {
        const PhaseSample s = phase_sample(c.phase, generic_wo(), {u0, u1});
        EXPECT_NEAR(length(s.wi), 1.0f, 1e-5f) << u0 << ", " << u1;
        EXPECT_TRUE(std::isfinite(s.pdf) && s.pdf > 0.0f) << u0 << ", " << u1;
      }
  }
}

TEST(Phase, SampledCosineFollowsPdf) {
  for (const Case& c : all_cases()) {
    SCOPED_TRACE(c.name);
    EXPECT_GT(p_value(c.phase, c.phase, 40, 1), kMinPValue);
  }
}

TEST(Phase, AzimuthIsUniformAndIndependentOfCosine) {
  for (const Case& c : all_cases()) {
    SCOPED_TRACE(c.name);
    EXPECT_GT(p_value(c.phase, c.phase, 8, 8), kMinPValue);
  }
}

TEST(Phase, ChiSquaredRejectsAWrongPdf) {
  // HG samples tested against a nearby g must fail decisively; so must a mixture with the
  // lobe weight off by 0.1, and Schlick's approximation tested as the HG it approximates.
  EXPECT_LT(p_value(HenyeyGreensteinPhase{0.5f}, HenyeyGreensteinPhase{0.6f}, 40, 1), 1e-9);
  EXPECT_LT(p_value(HenyeyGreensteinPhase{-0.3f}, HenyeyGreensteinPhase{-0.4f}, 40, 1), 1e-9);
  EXPECT_LT(p_value(DoubleHenyeyGreensteinPhase{0.5f, -0.3f, 0.7f},
                    DoubleHenyeyGreensteinPhase{0.5f, -0.3f, 0.6f}, 40, 1),
            1e-9);
  EXPECT_LT(p_value(SchlickPhase::from_g(0.8f), HenyeyGreensteinPhase{0.8f}, 40, 1), 1e-9);
}

// ---- Mean cosine ---------------------------------------------------------------------------------

TEST(Phase, MeanCosineMatchesQuadrature) {
  for (const Case& c : all_cases()) {
    SCOPED_TRACE(c.name);
    EXPECT_NEAR(phase_mean_cosine(c.phase), mean_cosine_by_quadrature(c.phase), 2e-4);
  }
}

TEST(Phase, MeanCosineMatchesSamples) {
  for (const Case& c : all_cases()) {
    SCOPED_TRACE(c.name);
    const Vec3 wo = generic_wo();
    Pcg32 rng(5, 7);
    double sum = 0.0, sum_sq = 0.0;
    for (int n = 0; n < kSamples; ++n) {
      const double mu = dot(wo, phase_sample(c.phase, wo, {rng.next_float(), rng.next_float()}).wi);
      sum += mu;
      sum_sq += mu * mu;
    }
    const double mean = sum / kSamples, variance = sum_sq / kSamples - mean * mean;
    EXPECT_NEAR(mean, phase_mean_cosine(c.phase), 5.0 * std::sqrt(variance / kSamples) + 1e-5);
  }
}

TEST(Phase, MeanCosineOfHenyeyGreensteinIsG) {
  for (float g : {-0.9f, 0.0f, 0.3f, 0.95f}) EXPECT_EQ(phase_mean_cosine(HenyeyGreensteinPhase{g}), g);
  EXPECT_EQ(phase_mean_cosine(IsotropicPhase{}), 0.0f);
  EXPECT_FLOAT_EQ(phase_mean_cosine(DoubleHenyeyGreensteinPhase{0.8f, -0.4f, 0.25f}),
                  0.25f * 0.8f - 0.75f * 0.4f);
}

TEST(Phase, SchlickMeanCosineIsContinuousAcrossItsSeriesBranch) {
  // Below |k| = 0.01 a series replaces the closed form; both must agree at the switch.
  for (float k : {0.01f, -0.01f}) {
    const float below = phase_mean_cosine(SchlickPhase{std::nextafter(k, 0.0f)});
    const float above = phase_mean_cosine(SchlickPhase{k});
    EXPECT_NEAR(below, above, 1e-7f);
    EXPECT_NEAR(above, 2.0f * k / 3.0f, 1e-6f);
  }
  EXPECT_EQ(phase_mean_cosine(SchlickPhase{0.0f}), 0.0f);
  // Schlick's k(g) fit matches HG's shape, not its mean cosine, which it overshoots a little:
  // 0.873 for g = 0.8, -0.760 for g = -0.7.
  for (float g : {-0.7f, 0.3f, 0.8f}) {
    const float mean = phase_mean_cosine(SchlickPhase::from_g(g));
    EXPECT_NEAR(mean, g, 0.1f) << g;
    EXPECT_GE(std::abs(mean), std::abs(g)) << g;
  }
}

// ---- Symmetry and closed-form values -------------------------------------------------------------

TEST(Phase, ValueDependsOnCosineOnly) {
  Pcg32 rng(9, 4);
  const auto random_unit = [&] {
    const float z = 1.0f - 2.0f * rng.next_float(), phi = 2.0f * kPi * rng.next_float();
    return spherical_direction(safe_sqrt(1.0f - z * z), z, phi);
  };
  for (const Case& c : all_cases()) {
    SCOPED_TRACE(c.name);
    for (int n = 0; n < 500; ++n) {
      const Vec3 wo = random_unit(), wi = random_unit();
      const Frame rotation = Frame::from_z(random_unit());
      const float value = phase_eval(c.phase, wo, wi);
      // Rotating both directions together: the same value up to the rounding of the cosine.
      EXPECT_NEAR(phase_eval(c.phase, rotation.to_world(wo), rotation.to_world(wi)), value, 1e-4f * value);
      // Reversing the path (reciprocity) gives exactly the same value.
      EXPECT_EQ(phase_eval(c.phase, -wi, -wo), value);
    }
  }
}

TEST(Phase, ScalarFormsHaveKnownValues) {
  for (float g : {-0.8f, -0.2f, 0.4f, 0.9f}) {
    EXPECT_FLOAT_EQ(henyey_greenstein(1.0f, g), (1.0f + g) / (4.0f * kPi * sqr(1.0f - g))) << g;
    EXPECT_FLOAT_EQ(henyey_greenstein(-1.0f, g), (1.0f - g) / (4.0f * kPi * sqr(1.0f + g))) << g;
    EXPECT_FLOAT_EQ(henyey_greenstein(0.3f, -g), henyey_greenstein(-0.3f, g)) << g;
    EXPECT_FLOAT_EQ(schlick(1.0f, g), (1.0f + g) / (4.0f * kPi * (1.0f - g))) << g;
    EXPECT_FLOAT_EQ(schlick(0.3f, -g), schlick(-0.3f, g)) << g;
  }
  for (float mu : {-1.0f, -0.2f, 0.7f, 1.0f}) {
    EXPECT_FLOAT_EQ(henyey_greenstein(mu, 0.0f), kInv4Pi);
    EXPECT_FLOAT_EQ(schlick(mu, 0.0f), kInv4Pi);
    EXPECT_FLOAT_EQ(
        phase_eval(IsotropicPhase{}, Vec3(0, 0, 1), spherical_direction(safe_sqrt(1 - mu * mu), mu, 1.0f)),
        kInv4Pi);
  }
}

TEST(Phase, SamplingIsMonotoneFromBackwardToForward) {
  // u.x = 0 scatters straight back and u.x -> 1 straight forward, for either sign of g.
  for (const Case& c : all_cases()) {
    SCOPED_TRACE(c.name);
    const Vec3 wo = generic_wo();
    if (std::holds_alternative<DoubleHenyeyGreensteinPhase>(c.phase)) continue;  // two lobes, two sweeps
    EXPECT_NEAR(dot(wo, phase_sample(c.phase, wo, {0.0f, 0.3f}).wi), -1.0f, 1e-5f);
    EXPECT_NEAR(dot(wo, phase_sample(c.phase, wo, {kOneMinusEpsilon, 0.3f}).wi), 1.0f, 1e-5f);
    float previous = -2.0f;
    for (int i = 0; i <= 100; ++i) {
      const float mu = dot(wo, phase_sample(c.phase, wo, {std::min(i / 100.0f, kOneMinusEpsilon), 0.7f}).wi);
      EXPECT_GE(mu, previous - 1e-6f) << i;
      previous = mu;
    }
  }
}

TEST(Phase, TinyGIsNearlyIsotropicWithoutSpecialCases) {
  // The factored inverse CDF never divides by g, so g -> 0 needs no isotropic branch and stays exact.
  for (float g : {1e-8f, -1e-8f, 1e-30f, 0.0f}) {
    Pcg32 rng(3, 3);
    for (int n = 0; n < 1000; ++n) {
      const Vec2 u{rng.next_float(), rng.next_float()};
      const PhaseSample s = phase_sample(HenyeyGreensteinPhase{g}, generic_wo(), u);
      const PhaseSample iso = phase_sample(IsotropicPhase{}, generic_wo(), u);
      EXPECT_NEAR(distance(s.wi, iso.wi), 0.0f, 1e-5f) << g;
      EXPECT_NEAR(s.pdf, kInv4Pi, 1e-6f) << g;
    }
  }
}

TEST(Phase, DoubleHenyeyGreensteinWithOneLobeIsThatLobe) {
  Pcg32 rng(2, 8);
  for (int n = 0; n < 1000; ++n) {
    const Vec2 u{rng.next_float(), rng.next_float()};
    const PhaseSample first = phase_sample(DoubleHenyeyGreensteinPhase{0.7f, -0.4f, 1.0f}, generic_wo(), u);
    const PhaseSample second = phase_sample(DoubleHenyeyGreensteinPhase{0.7f, -0.4f, 0.0f}, generic_wo(), u);
    // Equal up to rounding: the compiler may contract the two call sites differently.
    EXPECT_LT(distance(first.wi, phase_sample(HenyeyGreensteinPhase{0.7f}, generic_wo(), u).wi), 1e-6f);
    EXPECT_LT(distance(second.wi, phase_sample(HenyeyGreensteinPhase{-0.4f}, generic_wo(), u).wi), 1e-6f);
    EXPECT_FLOAT_EQ(first.pdf, henyey_greenstein(dot(generic_wo(), first.wi), 0.7f));
  }
}

}  // namespace caligo
