// Tests of equiangular distance sampling (equiangular.h) over setups that exercise all three
// regimes: the pdf integrates to one, samples follow it (chi-squared), invert undoes sample,
// samples stay in [a, b], and for a point light in a non-absorbing medium the estimator of the
// inverse-square integral has zero variance (Kulla & Fajardo 2012, section 3).
#include "lights/equiangular.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
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

// ---- Quadrature ----------------------------------------------------------------------------------

using Integrand = std::function<double(double)>;

double simpson(double a, double b, double fa, double fm, double fb) {
  return (b - a) / 6.0 * (fa + 4.0 * fm + fb);
}

// Adaptive Simpson (Richardson-corrected) on [a, b] given f at a, the midpoint and b.
double adaptive_simpson(const Integrand& f, double a, double b, double fa, double fm, double fb, double whole,
                        double tolerance, int depth) {
  const double m = 0.5 * (a + b), flm = f(0.5 * (a + m)), frm = f(0.5 * (m + b));
  const double left = simpson(a, m, fa, flm, fm), right = simpson(m, b, fm, frm, fb);
  const double error = left + right - whole;
  if (depth <= 0 || std::abs(error) <= 15.0 * tolerance) return left + right + error / 15.0;
  return adaptive_simpson(f, a, m, fa, flm, fm, left, 0.5 * tolerance, depth - 1) +
         adaptive_simpson(f, m, b, fm, frm, fb, right, 0.5 * tolerance, depth - 1);
}

// Integral of f over [a, b], split first at `breaks` (where f may peak) and into 16 panels
// each, so that no narrow peak hides between the first few Simpson nodes.
double integrate(const Integrand& f, double a, double b, std::vector<double> breaks = {}) {
  breaks.push_back(a);
  breaks.push_back(b);
  std::sort(breaks.begin(), breaks.end());
  double sum = 0.0;
  for (size_t i = 0; i + 1 < breaks.size(); ++i) {
    const double lo = std::max(a, breaks[i]), hi = std::min(b, breaks[i + 1]);
    for (int k = 0; k < 16 && hi > lo; ++k) {
      const double p0 = lo + (hi - lo) * k / 16.0, p1 = lo + (hi - lo) * (k + 1) / 16.0, pm = 0.5 * (p0 + p1);
      const double f0 = f(p0), fm = f(pm), f1 = f(p1);
      sum += adaptive_simpson(f, p0, p1, f0, fm, f1, simpson(p0, p1, f0, fm, f1), 1e-8, 30);
    }
  }
  return sum;
}

// ---- Setups --------------------------------------------------------------------------------------

struct Case {
  std::string name;
  EquiangularSetup s;
};

std::vector<Case> all_cases() {
  return {
      {"light beside the segment", {0.0f, 10.0f, 4.0f, 1.0f}},
      {"light far away", {0.0f, 10.0f, 5.0f, 1000.0f}},
      {"segment entirely before the foot point", {0.0f, 5.0f, 8.0f, 0.5f}},
      {"segment entirely after the foot point", {3.0f, 10.0f, 1.0f, 0.3f}},
      {"strongly peaked", {0.0f, 10.0f, 5.0f, 0.01f}},
      {"distant short segment", {100.0f, 101.0f, 50.0f, 2.0f}},
      {"flashlight: D = 0, light behind the origin", {0.0f, 10.0f, -2.0f, 0.0f}},
      {"D = 0, light ahead of the segment", {0.0f, 10.0f, 12.0f, 0.0f}},
      {"tiny D, light behind the origin", {0.0f, 10.0f, -1.0f, 1e-8f}},
      {"small D just above the collinear threshold", {0.0f, 10.0f, -1.0f, 1e-5f}},
      {"small D over the segment", {0.0f, 10.0f, 3.0f, 1e-3f}},
      {"D = 0 over the segment: uniform fallback", {0.0f, 10.0f, 3.0f, 0.0f}},
  };
}

double pdf_at(const EquiangularSetup& s, double t) { return EquiangularDistribution(s).pdf(float(t)); }

// Bin edges in t that do not come from the sampler: 32 uniform bins, refined geometrically
// towards the foot point so that a peak there spans many bins.
std::vector<double> bin_edges(const EquiangularSetup& s) {
  std::vector<double> edges;
  for (int i = 0; i <= 32; ++i) edges.push_back(s.a + (s.b - s.a) * i / 32.0);
  for (double r = std::max(double(s.D), 1e-3 * (s.b - s.a)) / 4.0; r < s.b - s.a; r *= 2.0)
    for (double e : {s.delta - r, s.delta + r})
      if (e > s.a && e < s.b) edges.push_back(e);
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

// Chi-squared p-value of `sample`'s distances against the pdf of `reference`.
double p_value(const std::function<float(float)>& sample, const EquiangularSetup& reference) {
  const std::vector<double> edges = bin_edges(reference);
  std::vector<double> expected(edges.size() - 1), observed(expected.size(), 0.0);
  const auto pdf = [&](double t) { return pdf_at(reference, t); };
  for (size_t i = 0; i < expected.size(); ++i) {
    std::vector<double> breaks;
    if (reference.delta > edges[i] && reference.delta < edges[i + 1]) breaks.push_back(reference.delta);
    expected[i] = kSamples * integrate(pdf, edges[i], edges[i + 1], breaks);
  }
  Pcg32 rng(21, 5);
  for (int n = 0; n < kSamples; ++n) {
    const double t = sample(rng.next_float());
    const auto bin = std::upper_bound(edges.begin(), edges.end(), t) - edges.begin() - 1;
    observed[size_t(std::clamp<ptrdiff_t>(bin, 0, ptrdiff_t(observed.size()) - 1))] += 1.0;
  }
  return chi2_p_value(observed, expected);
}

// Random numbers including both ends of [0, 1).
std::vector<float> test_us() {
  std::vector<float> us = {0.0f, 1e-7f, 0.5f, 1.0f - 1e-7f, kOneMinusEpsilon};
  Pcg32 rng(4, 4);
  for (int n = 0; n < 20000; ++n) us.push_back(rng.next_float());
  return us;
}

}  // namespace

// ---- Normalisation and support -------------------------------------------------------------------

TEST(Equiangular, PdfIntegratesToOne) {
  for (const Case& c : all_cases()) {
    SCOPED_TRACE(c.name);
    const std::vector<double> breaks = {double(c.s.delta)};
    EXPECT_NEAR(integrate([&](double t) { return pdf_at(c.s, t); }, c.s.a, c.s.b, breaks), 1.0, 1e-3);
  }
}

TEST(Equiangular, PdfIsFinitePositiveInsideAndZeroOutside) {
  for (const Case& c : all_cases()) {
    SCOPED_TRACE(c.name);
    for (int i = 0; i <= 1000; ++i) {
      const float t = lerp(i / 1000.0f, c.s.a, c.s.b);
      const float pdf = EquiangularDistribution(c.s).pdf(t);
      EXPECT_TRUE(std::isfinite(pdf) && pdf > 0.0f) << "t = " << t << ", pdf = " << pdf;
    }
    EXPECT_EQ(EquiangularDistribution(c.s).pdf(std::nextafter(c.s.a, -kInfinity)), 0.0f);
    EXPECT_EQ(EquiangularDistribution(c.s).pdf(std::nextafter(c.s.b, kInfinity)), 0.0f);
  }
}

// ---- Sampling ------------------------------------------------------------------------------------

TEST(Equiangular, SamplesStayInTheSegmentAndGrowWithU) {
  for (const Case& c : all_cases()) {
    SCOPED_TRACE(c.name);
    for (float u : test_us()) {
      const float t = EquiangularDistribution(c.s).sample(u);
      ASSERT_GE(t, c.s.a) << "u = " << u;
      ASSERT_LE(t, c.s.b) << "u = " << u;
    }
    float previous = c.s.a;
    for (int i = 0; i <= 1000; ++i) {
      const float t = EquiangularDistribution(c.s).sample(std::min(i / 1000.0f, kOneMinusEpsilon));
      ASSERT_GE(t, previous) << i;
      previous = t;
    }
  }
}

TEST(Equiangular, SamplesFollowPdf) {
  for (const Case& c : all_cases()) {
    SCOPED_TRACE(c.name);
    EXPECT_GT(p_value([&](float u) { return EquiangularDistribution(c.s).sample(u); }, c.s), kMinPValue);
  }
}

TEST(Equiangular, ChiSquaredRejectsUniformSamplesForAPeakedSetup) {
  const EquiangularSetup peaked{0.0f, 10.0f, 5.0f, 0.1f};
  EXPECT_LT(p_value([&](float u) { return lerp(u, peaked.a, peaked.b); }, peaked), 1e-9);
  // A subtler error: samples for a light 20% farther from the ray.
  const EquiangularSetup farther{0.0f, 10.0f, 5.0f, 0.12f};
  EXPECT_LT(p_value([&](float u) { return EquiangularDistribution(farther).sample(u); }, peaked), 1e-9);
}

TEST(Equiangular, InvertUndoesSample) {
  for (const Case& c : all_cases()) {
    SCOPED_TRACE(c.name);
    for (float u : test_us()) {
      const float t = EquiangularDistribution(c.s).sample(u);
      // Rounding t to a float moves u by up to pdf(t) * ulp(t) / 2, large at a sharp peak.
      const float quantisation = EquiangularDistribution(c.s).pdf(t) * std::abs(t) * 0x1p-23f;
      ASSERT_NEAR(EquiangularDistribution(c.s).invert(t), u, 1e-4f + quantisation) << "u = " << u << ", t = " << t;
    }
    EXPECT_EQ(EquiangularDistribution(c.s).invert(c.s.a), 0.0f);
    EXPECT_EQ(EquiangularDistribution(c.s).invert(c.s.b), 1.0f);
  }
}

TEST(Equiangular, RegimesJoinContinuouslyAtTheCollinearThreshold) {
  // D = 1e-6 |x_near| switches from the Cauchy form to the inverse-square one.
  const float near = 2.0f;
  for (float factor : {0.999f, 1.001f}) {
    const EquiangularSetup s{0.0f, 10.0f, -near, 1e-6f * near * factor};
    const EquiangularSetup collinear{0.0f, 10.0f, -near, 0.0f};
    for (float t : {0.0f, 0.5f, 3.0f, 10.0f})
      EXPECT_NEAR(EquiangularDistribution(s).pdf(t), EquiangularDistribution(collinear).pdf(t),
                  1e-5f * EquiangularDistribution(collinear).pdf(t));
    for (float u : {0.0f, 0.25f, 0.9f})
      EXPECT_NEAR(EquiangularDistribution(s).sample(u), EquiangularDistribution(collinear).sample(u), 1e-5f);
  }
}

TEST(Equiangular, UniformFallbackWhenTheLightIsOnTheSegment) {
  const EquiangularSetup s{2.0f, 6.0f, 3.0f, 0.0f};
  EXPECT_FLOAT_EQ(EquiangularDistribution(s).pdf(2.5f), 0.25f);
  EXPECT_FLOAT_EQ(EquiangularDistribution(s).pdf(3.0f), 0.25f);
  EXPECT_FLOAT_EQ(EquiangularDistribution(s).sample(0.5f), 4.0f);
  EXPECT_FLOAT_EQ(EquiangularDistribution(s).invert(5.0f), 0.75f);
}

TEST(Equiangular, HalfInfiniteSegment) {
  // A ray that never leaves the medium: both non-uniform regimes have closed forms on [a, inf).
  for (float D : {0.5f, 0.0f}) {
    SCOPED_TRACE(D);
    const EquiangularSetup s{1.0f, kInfinity, -1.0f, D};
    for (float u : test_us()) {
      const float t = EquiangularDistribution(s).sample(u);
      ASSERT_TRUE(t >= 1.0f && std::isfinite(t)) << "u = " << u;
      ASSERT_NEAR(EquiangularDistribution(s).invert(t), u, 1e-4f) << "u = " << u;
    }
    // x = t - delta = 2 at t = 1: Cauchy span pi/2 - atan(2 / D), inverse-square K = 1/2.
    const double expected = D > 0.0f ? D / ((0.5 * kPi - std::atan(2.0 / D)) * (D * D + 4.0)) : 2.0 / 4.0;
    EXPECT_FLOAT_EQ(EquiangularDistribution(s).pdf(1.0f), float(expected));
    EXPECT_GT(EquiangularDistribution(s).pdf(1e15f), 0.0f);
  }
}

// ---- The setup from ray and light ----------------------------------------------------------------

TEST(Equiangular, SetupFromRayAndLight) {
  const Vec3 origin(1.0f, 2.0f, 3.0f), dir = normalize(Vec3(1.0f, 1.0f, 0.0f));
  const Vec3 perpendicular(0.0f, 0.0f, 1.0f);
  const EquiangularSetup s =
      make_equiangular_setup(origin, dir, origin + dir * 4.0f + perpendicular * 0.5f, 0.f, 9.f);
  EXPECT_EQ(s.a, 0.0f);
  EXPECT_EQ(s.b, 9.0f);
  EXPECT_NEAR(s.delta, 4.0f, 1e-5f);
  EXPECT_NEAR(s.D, 0.5f, 1e-5f);
  // A light behind the origin, on the ray's line.
  const EquiangularSetup behind = make_equiangular_setup(origin, dir, origin - dir * 2.0f, 0.0f, 9.0f);
  EXPECT_NEAR(behind.delta, -2.0f, 1e-5f);
  EXPECT_NEAR(behind.D, 0.0f, 1e-5f);
}

// ---- Zero variance for a point light -------------------------------------------------------------

// I = integral over [a, b] of 1 / (D^2 + (t - delta)^2) dt = (theta_b - theta_a) / D in closed form;
// equiangular sampling makes every single-sample estimate f / pdf equal to it.
TEST(Equiangular, PointLightInverseSquareIntegralHasZeroVariance) {
  const Vec3 origin(1.0f, 2.0f, 3.0f), dir = normalize(Vec3(1.0f, 1.0f, 0.0f)),
                                       perpendicular(0.0f, 0.0f, 1.0f);
  const float a = 0.0f, b = 10.0f, delta = 4.0f;
  for (float D : {2.0f, 0.5f, 0.05f}) {
    SCOPED_TRACE(D);
    const Vec3 light = origin + dir * delta + perpendicular * D;
    const EquiangularSetup s = make_equiangular_setup(origin, dir, light, a, b);
    const double closed_form = (std::atan((b - delta) / D) - std::atan((a - delta) / D)) / D;
    const auto integrand = [&](double t) { return 1.0 / (double(D) * D + (t - delta) * (t - delta)); };
    EXPECT_NEAR(integrate(integrand, a, b, {double(delta)}), closed_form, 1e-6 * closed_form);
    for (float u : test_us()) {
      const float t = EquiangularDistribution(s).sample(u);
      const double f = 1.0 / double(length_squared(light - (origin + dir * t)));  // from the geometry
      ASSERT_NEAR(f / EquiangularDistribution(s).pdf(t), closed_form, 1e-4 * closed_form) << "u = " << u << ", t = " << t;
    }
  }
}

// The flashlight: a light on the ray's line behind the origin, where 1 / (t - delta)^2 is
// integrated exactly by the inverse-square regime: I = 1/(a - delta) - 1/(b - delta).
TEST(Equiangular, FlashlightInverseSquareIntegralHasZeroVariance) {
  const Vec3 origin(1.0f, 2.0f, 3.0f), dir = normalize(Vec3(0.0f, 1.0f, 1.0f));
  const Vec3 light = origin - dir * 1.5f;
  const EquiangularSetup s = make_equiangular_setup(origin, dir, light, 0.0f, 20.0f);
  const double closed_form = 1.0 / 1.5 - 1.0 / 21.5;
  for (float u : test_us()) {
    const float t = EquiangularDistribution(s).sample(u);
    const double f = 1.0 / double(length_squared(light - (origin + dir * t)));
    ASSERT_NEAR(f / EquiangularDistribution(s).pdf(t), closed_form, 1e-4 * closed_form) << "u = " << u;
  }
}

}  // namespace caligo
