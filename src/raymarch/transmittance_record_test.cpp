// Tests of the TransmittanceRecord: analytic slabs, lookups against a brute-force scan of the steps,
// and statistical tests of both distance samplers (normalisation, sample/pdf agreement, chi-squared
// goodness of fit, unbiasedness per channel of chromatic media).
#include "raymarch/transmittance_record.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <vector>

#include "core/math.h"
#include "core/rng.h"
#include "core/testing/chi_squared.h"

namespace caligo {
namespace {

// ---- Chi-squared machinery (as in core/sampling_test.cpp) --------------------------------------

using test_stats::chi2_p_value;
using test_stats::chi2_survival;

// ---- Records and brute-force references --------------------------------------------------------

struct StepSpec {
  float t0, t1;
  RGB sigma_t, sigma_s;
};

TransmittanceRecord make_record(const std::vector<StepSpec>& steps) {
  TransmittanceRecord record;
  for (const StepSpec& s : steps) record.push(s.t0, s.t1, s.sigma_t, s.sigma_s, {});
  return record;
}

// Chromatic, with a gap [1.0, 1.7), a clear-and-dark blue step and a thick last step.
const std::vector<StepSpec> kChromatic = {
    {0.0f, 0.6f, RGB(1.5f, 0.5f, 3.0f), RGB(1.0f, 0.4f, 2.0f)},
    {0.6f, 1.0f, RGB(0.2f, 2.5f, 0.0f), RGB(0.2f, 2.0f, 0.0f)},
    {1.7f, 2.5f, RGB(0.8f, 0.3f, 1.2f), RGB(0.0f, 0.3f, 1.0f)},
    {2.5f, 2.6f, RGB(6.0f, 6.0f, 0.5f), RGB(5.0f, 1.0f, 0.4f)},
};

// Channel 1 never collides; the others leave T_end around 0.05.
const std::vector<StepSpec> kFreeFlight = {
    {0.0f, 0.5f, RGB(1.0f, 0.0f, 2.0f), RGB(0.5f, 0.0f, 1.0f)},
    {0.5f, 1.2f, RGB(0.5f, 0.0f, 3.0f), RGB(0.5f, 0.0f, 1.0f)},
    {2.0f, 3.0f, RGB(2.0f, 0.0f, 0.1f), RGB(1.0f, 0.0f, 0.1f)},
};

int brute_find_step(const std::vector<StepSpec>& steps, double t) {
  for (size_t i = 0; i < steps.size(); ++i)
    if (steps[i].t0 <= t && t < steps[i].t1) return int(i);
  return -1;
}

double brute_transmittance(const std::vector<StepSpec>& steps, int c, double t) {
  double tau = 0.0;
  for (const StepSpec& s : steps) tau += s.sigma_t[c] * std::clamp(t - s.t0, 0.0, double(s.t1 - s.t0));
  return std::exp(-tau);
}

double brute_coefficient(const std::vector<StepSpec>& steps, bool scattering, int c, double t) {
  const int i = brute_find_step(steps, t);
  return i < 0 ? 0.0 : (scattering ? steps[i].sigma_s[c] : steps[i].sigma_t[c]);
}

std::vector<double> step_ends(const std::vector<StepSpec>& steps) {
  std::vector<double> out;
  for (const StepSpec& s : steps) out.insert(out.end(), {s.t0, s.t1});
  return out;
}

// Integral of f over [a, b], split where f may jump and integrated piecewise with 5-point
// Gauss-Legendre on 16 sub-intervals per piece (the nodes never touch a jump).
double integrate(const std::function<double(double)>& f, double a, double b,
                 const std::vector<double>& breaks) {
  static constexpr double kNode[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                                      0.9061798459386640};
  static constexpr double kWeight[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                        0.4786286704993665, 0.2369268850561891};
  std::vector<double> cuts{a, b};
  for (double x : breaks)
    if (x > a && x < b) cuts.push_back(x);
  std::sort(cuts.begin(), cuts.end());
  double sum = 0.0;
  for (size_t p = 0; p + 1 < cuts.size(); ++p) {
    const double h = (cuts[p + 1] - cuts[p]) / 16.0;
    for (int k = 0; k < 16; ++k) {
      const double mid = cuts[p] + (k + 0.5) * h;
      for (int n = 0; n < 5; ++n) sum += 0.5 * h * kWeight[n] * f(mid + 0.5 * h * kNode[n]);
    }
  }
  return sum;
}

// Exact per-channel integral of sigma_s T over the record (the sampler's W_c), by quadrature.
double brute_scatter_total(const std::vector<StepSpec>& steps, int c) {
  const auto f = [&](double t) {
    return brute_coefficient(steps, true, c, t) * brute_transmittance(steps, c, t);
  };
  return integrate(f, steps.front().t0, steps.back().t1, step_ends(steps));
}

// Expected counts in `bins` equal bins over [a, b) for `n` samples of the (sub-)density `pdf`.
std::vector<double> expected_counts(const std::function<double(double)>& pdf, double a, double b, int bins,
                                    int n, const std::vector<double>& breaks) {
  std::vector<double> out(bins);
  for (int i = 0; i < bins; ++i)
    out[i] = n * integrate(pdf, a + (b - a) * i / bins, a + (b - a) * (i + 1) / bins, breaks);
  return out;
}

int bin_of(double t, double a, double b, int bins) {
  return std::clamp(int((t - a) / (b - a) * bins), 0, bins - 1);
}

void expect_relative(double actual, double expected, double tolerance, const char* what) {
  EXPECT_NEAR(actual, expected, tolerance * std::abs(expected) + 1e-30) << what;
}

// ---- Construction and lookups ------------------------------------------------------------------

TEST(TransmittanceRecord, EmptyRecord) {
  const TransmittanceRecord r;
  EXPECT_TRUE(r.empty());
  EXPECT_EQ(r.t_begin(), 0.0f);
  EXPECT_EQ(r.t_end(), 0.0f);
  EXPECT_EQ(r.find_step(0.0f), -1);
  EXPECT_EQ(r.transmittance(5.0f), RGB(1.0f));
  EXPECT_EQ(r.transmittance_end(), RGB(1.0f));
  EXPECT_FALSE(r.sample_scatter_density(0.5f, 0.5f));
  EXPECT_FALSE(r.sample_free_flight(0.5f, 0.5f));
  EXPECT_EQ(r.scatter_density_pdf(0.0f), 0.0f);
  EXPECT_EQ(r.free_flight_pdf(0.0f), 0.0f);
  EXPECT_EQ(r.scatter_weight_total(), 0.0f);
}

TEST(TransmittanceRecord, ChromaticSlabFollowsBeerLambert) {
  const RGB sigma(0.5f, 1.0f, 2.0f);
  const TransmittanceRecord r = make_record({{1.0f, 3.0f, sigma, sigma * 0.5f}});
  for (int c = 0; c < 3; ++c) {
    expect_relative(r.transmittance(3.0f)[c], std::exp(-2.0 * sigma[c]), 1e-6, "T(t1)");
    expect_relative(r.transmittance_end()[c], std::exp(-2.0 * sigma[c]), 1e-6, "T(end)");
    expect_relative(r.transmittance(2.0f)[c], std::exp(-1.0 * sigma[c]), 1e-6, "T(mid)");
    expect_relative(r.transmittance(9.0f)[c], std::exp(-2.0 * sigma[c]), 1e-6, "T(after)");
  }
  EXPECT_EQ(r.transmittance(0.5f), RGB(1.0f));
  EXPECT_EQ(r.t_begin(), 1.0f);
  EXPECT_EQ(r.t_end(), 3.0f);
}

TEST(TransmittanceRecord, OpticallyThinStepKeepsPrecision) {
  // 1 - exp(-x) without expm1 would lose every digit here.
  const TransmittanceRecord r = make_record({{0.0f, 2.0f, RGB(1e-9f), RGB(1e-9f)}});
  expect_relative(r.scatter_weight_total(), 2e-9, 1e-6, "thin scatter integral");
  const auto s = r.sample_scatter_density(0.5f, 0.25f);
  ASSERT_TRUE(s);
  EXPECT_NEAR(s->t, 0.5f, 1e-6f);
  expect_relative(s->pdf, 0.5, 1e-6, "uniform pdf");
}

std::vector<StepSpec> random_steps(Pcg32& rng, int n) {
  const auto coefficient = [&] { return rng.next_float() < 0.15f ? 0.0f : 2.0f * rng.next_float(); };
  std::vector<StepSpec> steps;
  float t = rng.next_float();
  for (int i = 0; i < n; ++i) {
    if (rng.next_float() < 0.3f) t += 0.3f * rng.next_float();  // a gap (vacuum)
    const float t1 = t + 0.01f + 0.5f * rng.next_float();
    const RGB sigma_t(coefficient(), coefficient(), coefficient());
    steps.push_back({t, t1, sigma_t, sigma_t * RGB(rng.next_float(), rng.next_float(), rng.next_float())});
    t = t1;
  }
  return steps;
}

TEST(TransmittanceRecord, LookupsMatchBruteForce) {
  Pcg32 rng(3, 11);
  const std::vector<StepSpec> steps = random_steps(rng, 50);
  const TransmittanceRecord r = make_record(steps);
  ASSERT_EQ(r.steps().size(), steps.size());
  std::vector<float> probes = {r.t_begin() - 1.0f, r.t_end(), r.t_end() + 1.0f};
  for (const StepSpec& s : steps) probes.insert(probes.end(), {s.t0, s.t1});
  for (int i = 0; i < 4000; ++i)
    probes.push_back(r.t_begin() - 0.5f + (r.t_end() - r.t_begin() + 1.0f) * rng.next_float());
  for (float t : probes) {
    ASSERT_EQ(r.find_step(t), brute_find_step(steps, t)) << "t = " << t;
    const RGB tr = r.transmittance(t);
    for (int c = 0; c < 3; ++c)
      expect_relative(tr[c], brute_transmittance(steps, c, t), 1e-5, "transmittance");
    if (HasFailure()) return;
  }
}

TEST(TransmittanceRecord, StepsStoreTheirPrefixes) {
  const TransmittanceRecord r = make_record(kChromatic);
  for (size_t i = 0; i < kChromatic.size(); ++i) {
    const MarchStep& s = r.steps()[i];
    for (int c = 0; c < 3; ++c) {
      expect_relative(s.transmittance[c], brute_transmittance(kChromatic, c, s.t0), 1e-6, "T(t0)");
      const std::vector<StepSpec> before(kChromatic.begin(), kChromatic.begin() + i);
      if (i > 0) expect_relative(s.scatter_before[c], brute_scatter_total(before, c), 1e-5, "scatter_before");
    }
  }
}

TEST(TransmittanceRecord, PushDropsEmptyStepsAndRejectsOverlap) {
  TransmittanceRecord r;
  r.push(0.0f, 1.0f, RGB(1.0f), RGB(0.5f), {});
  r.push(1.0f, 1.0f, RGB(1.0f), RGB(0.5f), {});
  EXPECT_EQ(r.steps().size(), 1u);
  EXPECT_THROW(r.push(0.5f, 2.0f, RGB(1.0f), RGB(0.5f), {}), std::logic_error);
  // An overlap of a few ulps (t0 + dt * i rounding) is absorbed by starting at the previous end.
  r.push(std::nextafter(1.0f, 0.0f), 2.0f, RGB(1.0f), RGB(0.5f), {});
  ASSERT_EQ(r.steps().size(), 2u);
  EXPECT_EQ(r.steps()[1].t0, 1.0f);
}

TEST(TransmittanceRecord, ClearKeepsCapacityAndEmission) {
  const std::vector<PhaseLobe> lobes = {{RGB(1.0f), IsotropicPhase{}}};
  TransmittanceRecord r;
  const auto fill = [&] {
    for (int i = 0; i < 40; ++i) r.push(float(i), float(i + 1), RGB(0.1f), RGB(0.05f), lobes);
  };
  fill();
  r.add_emission(RGB(1.0f, 2.0f, 3.0f));
  r.add_emission(RGB(0.5f));
  EXPECT_EQ(r.emission(), RGB(1.5f, 2.5f, 3.5f));
  const MarchStep* steps = r.steps().data();
  const PhaseLobe* first_lobes = r.lobes(r.steps()[0]).data();
  r.clear();
  EXPECT_TRUE(r.empty());
  EXPECT_EQ(r.emission(), RGB(0.0f));
  fill();
  EXPECT_EQ(r.steps().data(), steps);
  EXPECT_EQ(r.lobes(r.steps()[0]).data(), first_lobes);
}

TEST(TransmittanceRecord, LobesReturnsThePushedLobes) {
  TransmittanceRecord r;
  const std::vector<PhaseLobe> two = {{RGB(0.25f), IsotropicPhase{}},
                                      {RGB(0.75f), HenyeyGreensteinPhase{0.6f}}};
  const std::vector<PhaseLobe> one = {{RGB(1.0f), SchlickPhase{-0.3f}}};
  r.push(0.0f, 1.0f, RGB(1.0f), RGB(1.0f), two);
  r.push(1.0f, 2.0f, RGB(1.0f), RGB(0.0f), {});
  r.push(3.0f, 4.0f, RGB(1.0f), RGB(1.0f), one);
  const auto a = r.lobes(r.steps()[0]), b = r.lobes(r.steps()[1]), c = r.lobes(r.steps()[2]);
  ASSERT_EQ(a.size(), 2u);
  EXPECT_EQ(a[0].weight, RGB(0.25f));
  EXPECT_TRUE(std::holds_alternative<IsotropicPhase>(a[0].phase));
  EXPECT_EQ(a[1].weight, RGB(0.75f));
  EXPECT_EQ(std::get<HenyeyGreensteinPhase>(a[1].phase).g, 0.6f);
  EXPECT_TRUE(b.empty());
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(std::get<SchlickPhase>(c[0].phase).k, -0.3f);
}

// ---- Scatter-density sampling ------------------------------------------------------------------

TEST(ScatterDensity, NoScatteringGivesNoSample) {
  const TransmittanceRecord r = make_record({{0.0f, 1.0f, RGB(1.0f), RGB(0.0f)}});
  EXPECT_FALSE(r.sample_scatter_density(0.3f, 0.7f));
  EXPECT_EQ(r.scatter_density_pdf(0.5f), 0.0f);
}

TEST(ScatterDensity, PdfIntegratesToOne) {
  const TransmittanceRecord r = make_record(kChromatic);
  const auto pdf = [&](double t) { return double(r.scatter_density_pdf(float(t))); };
  EXPECT_NEAR(integrate(pdf, -1.0, 4.0, step_ends(kChromatic)), 1.0, 1e-3);
  double average = 0.0;
  for (int c = 0; c < 3; ++c) average += brute_scatter_total(kChromatic, c) / 3.0;
  expect_relative(r.scatter_weight_total(), average, 1e-5, "scatter_weight_total");
}

// Draws n density samples, checking each against the record, and bins them over [t_begin, t_end).
std::vector<double> scatter_histogram(const TransmittanceRecord& r, int n, int bins, uint64_t seed) {
  Pcg32 rng(seed, 5);
  std::vector<double> counts(bins, 0.0);
  for (int i = 0; i < n; ++i) {
    const float uc = rng.next_float(), ud = rng.next_float();
    const auto s = r.sample_scatter_density(uc, ud);
    EXPECT_TRUE(s);
    if (!s) break;
    const MarchStep& step = r.steps()[s->step];
    EXPECT_TRUE(s->t >= step.t0 && s->t < step.t1) << s->t;
    EXPECT_TRUE(s->pdf > 0.0f && std::isfinite(s->pdf));
    EXPECT_NEAR(s->pdf, r.scatter_density_pdf(s->t), 1e-6f * s->pdf);
    if (::testing::Test::HasFailure()) break;
    counts[bin_of(s->t, r.t_begin(), r.t_end(), bins)] += 1.0;
  }
  return counts;
}

constexpr int kSamples = 100000;
constexpr int kBins = 64;

TEST(ScatterDensity, SamplesFollowPdf) {
  const TransmittanceRecord r = make_record(kChromatic);
  const std::vector<double> observed = scatter_histogram(r, kSamples, kBins, 17);
  const auto pdf = [&](double t) { return double(r.scatter_density_pdf(float(t))); };
  const auto expected = expected_counts(pdf, r.t_begin(), r.t_end(), kBins, kSamples, step_ends(kChromatic));
  EXPECT_GT(chi2_p_value(observed, expected), 1e-3);
}

TEST(ScatterDensity, ChiSquaredRejectsWrongPdfs) {
  const TransmittanceRecord r = make_record(kChromatic);
  const std::vector<double> observed = scatter_histogram(r, kSamples, kBins, 17);
  const std::vector<double> breaks = step_ends(kChromatic);
  // Two plausible bugs: the density of one channel only, and T frozen at each step's start.
  const auto green_only = [&](double t) {
    return brute_coefficient(kChromatic, true, 1, t) * brute_transmittance(kChromatic, 1, t);
  };
  const auto frozen = [&](double t) {
    const int i = r.find_step(float(t));
    return i < 0 ? 0.0 : double((r.steps()[i].sigma_s * r.steps()[i].transmittance).average());
  };
  for (const std::function<double(double)>& wrong :
       {std::function<double(double)>(green_only), std::function<double(double)>(frozen)}) {
    const double norm = integrate(wrong, r.t_begin(), r.t_end(), breaks);
    const auto pdf = [&](double t) { return wrong(t) / norm; };
    const auto expected = expected_counts(pdf, r.t_begin(), r.t_end(), kBins, kSamples, breaks);
    EXPECT_LT(chi2_p_value(observed, expected), 1e-3);
  }
}

TEST(ScatterDensity, EstimatorIsUnbiasedPerChannel) {
  // E[sigma_s,c T_c / pdf] = W_c for every channel only if the pdf accounts for how each channel
  // was chosen: the channel-averaged pdf must be used, not the chosen channel's own.
  const TransmittanceRecord r = make_record(kChromatic);
  Pcg32 rng(23, 1);
  double sum[3] = {0, 0, 0};
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const auto s = r.sample_scatter_density(rng.next_float(), rng.next_float());
    ASSERT_TRUE(s);
    const RGB value = r.steps()[s->step].sigma_s * r.transmittance(s->t);
    for (int c = 0; c < 3; ++c) sum[c] += value[c] / s->pdf;
  }
  for (int c = 0; c < 3; ++c) expect_relative(sum[c] / n, brute_scatter_total(kChromatic, c), 0.01, "W_c");
}

// ---- Free-flight sampling ----------------------------------------------------------------------

TEST(FreeFlight, PdfIntegratesToCollisionProbability) {
  const TransmittanceRecord r = make_record(kFreeFlight);
  double pass = 0.0;
  for (int c = 0; c < 3; ++c) pass += brute_transmittance(kFreeFlight, c, 10.0) / 3.0;
  expect_relative(r.transmittance_end().average(), pass, 1e-6, "avg T(end)");
  const auto pdf = [&](double t) { return double(r.free_flight_pdf(float(t))); };
  EXPECT_NEAR(integrate(pdf, -1.0, 4.0, step_ends(kFreeFlight)), 1.0 - pass, 1e-3);
}

TEST(FreeFlight, SamplesFollowPdfAndPassThroughAtTheRightRate) {
  const TransmittanceRecord r = make_record(kFreeFlight);
  Pcg32 rng(29, 3);
  std::vector<double> observed(kBins + 1, 0.0);  // the last bin counts rays passing the record
  double estimate[3] = {0, 0, 0};
  for (int i = 0; i < kSamples; ++i) {
    const auto s = r.sample_free_flight(rng.next_float(), rng.next_float());
    if (!s) {
      observed[kBins] += 1.0;
      continue;
    }
    const MarchStep& step = r.steps()[s->step];
    ASSERT_TRUE(s->t >= step.t0 && s->t < step.t1) << s->t;
    ASSERT_TRUE(s->pdf > 0.0f && std::isfinite(s->pdf));
    ASSERT_NEAR(s->pdf, r.free_flight_pdf(s->t), 1e-6f * s->pdf);
    observed[bin_of(s->t, r.t_begin(), r.t_end(), kBins)] += 1.0;
    const RGB value = step.sigma_t * r.transmittance(s->t);
    for (int c = 0; c < 3; ++c) estimate[c] += value[c] / s->pdf;
  }
  const double pass = r.transmittance_end().average();
  const double sigma = std::sqrt(pass * (1.0 - pass) / kSamples);
  EXPECT_NEAR(observed[kBins] / kSamples, pass, 4.0 * sigma);

  const auto pdf = [&](double t) { return double(r.free_flight_pdf(float(t))); };
  std::vector<double> expected =
      expected_counts(pdf, r.t_begin(), r.t_end(), kBins, kSamples, step_ends(kFreeFlight));
  expected.push_back(pass * kSamples);
  EXPECT_GT(chi2_p_value(observed, expected), 1e-3);
  // Per channel, collisions estimate the collision probability 1 - T_c(end) without bias.
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(estimate[c] / kSamples, 1.0 - brute_transmittance(kFreeFlight, c, 10.0), 0.01) << c;
}

TEST(FreeFlight, ClearChannelNeverCollides) {
  const TransmittanceRecord r = make_record(kFreeFlight);
  for (float u : {0.0f, 0.3f, 0.9f, kOneMinusEpsilon}) EXPECT_FALSE(r.sample_free_flight(0.5f, u)) << u;
}

// ---- Extremes ----------------------------------------------------------------------------------

TEST(TransmittanceRecord, ExtremeSamplesStayInsideTheirStep) {
  const TransmittanceRecord r = make_record({
      {0.0f, 1.0f, RGB(1e-9f, 0.0f, 1e-12f), RGB(1e-9f, 0.0f, 1e-12f)},
      {1.0f, 2.0f, RGB(1000.0f, 40.0f, 0.01f), RGB(900.0f, 1.0f, 0.005f)},
      {5.0f, 5.5f, RGB(80.0f), RGB(80.0f)},
  });
  const float us[] = {0.0f, 1e-7f, 0.25f, 0.5f, 0.999f, kOneMinusEpsilon};
  for (float uc : us) {
    for (float ud : us) {
      for (const auto& s : {r.sample_scatter_density(uc, ud), r.sample_free_flight(uc, ud)}) {
        if (!s) continue;
        ASSERT_GE(s->step, 0);
        const MarchStep& step = r.steps()[s->step];
        EXPECT_TRUE(s->t >= step.t0 && s->t < step.t1) << uc << " " << ud << " t = " << s->t;
        EXPECT_EQ(r.find_step(s->t), s->step);
        EXPECT_TRUE(s->pdf > 0.0f && std::isfinite(s->pdf)) << uc << " " << ud << " pdf = " << s->pdf;
      }
    }
  }
}

// ---- Surface layers (partly transparent surfaces) ----------------------------------------------

// Layers inside the first step, in the gap, coincident pair past the end: T before and after
// each against the brute force times the factors in front, per channel.
TEST(TransmittanceRecordLayers, TransmittanceDropsAtEachLayer) {
  TransmittanceRecord r = make_record(kChromatic);
  const std::vector<SurfaceLayer> layers = {
      {0.3f, 0.5f, {}}, {1.2f, 0.25f, {}}, {2.8f, 0.4f, {}}, {2.8f, 0.5f, {}}};
  r.insert_layers(layers);
  ASSERT_EQ(r.layers().size(), 4u);
  const auto factor = [&](double t) {
    double f = 1.0;
    for (const SurfaceLayer& l : layers)
      if (l.t <= t) f *= 1.0 - l.opacity;
    return f;
  };
  for (double t : {0.1, 0.29, 0.31, 0.9, 1.1, 1.3, 2.0, 2.55, 2.7, 3.5})
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(r.transmittance(float(t))[c], brute_transmittance(kChromatic, c, t) * factor(t), 1e-6)
          << "t = " << t << " channel " << c;
  RGB totals;
  for (const SurfaceLayer& l : r.layers()) {
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(l.before[c], brute_transmittance(kChromatic, c, l.t) * factor(std::nextafter(l.t, 0.0f)) *
                                   (&l == &r.layers()[3] ? 0.6 : 1.0),
                  1e-6);
    totals += l.before * l.opacity;
  }
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(r.layer_totals()[c], totals[c], 1e-6f);
    EXPECT_NEAR(r.transmittance_end()[c], brute_transmittance(kChromatic, c, 3.0) * factor(3.0), 1e-6);
  }
}

// Energy per channel: scatter + meet a layer + absorb + pass = 1, with the absorbed part from the
// brute force; and the scatter integral over the split steps is the brute force's behind factors.
TEST(TransmittanceRecordLayers, ScatterIntegralSeesTheLayers) {
  TransmittanceRecord r = make_record(kChromatic);
  const std::vector<SurfaceLayer> layers = {{0.3f, 0.5f, {}}, {1.2f, 0.25f, {}}, {2.55f, 0.4f, {}}};
  r.insert_layers(layers);
  const auto factor = [&](double t) {
    double f = 1.0;
    for (const SurfaceLayer& l : layers)
      if (l.t <= t) f *= 1.0 - l.opacity;
    return f;
  };
  for (int c = 0; c < 3; ++c) {
    const auto density = [&](double t) {
      return brute_coefficient(kChromatic, true, c, t) * brute_transmittance(kChromatic, c, t) * factor(t);
    };
    std::vector<double> breaks = step_ends(kChromatic);
    for (const SurfaceLayer& l : layers) breaks.push_back(l.t);
    std::sort(breaks.begin(), breaks.end());
    EXPECT_NEAR(r.scatter_totals()[c], integrate(density, 0.0, 2.6, breaks), 1e-5) << c;
  }
}

// Free flight meets a layer with probability opacity x T in front (avg over channels when the
// channel is drawn), in a grey record: 400,000 draws, each layer's frequency within 4 binomial
// standard errors; sample_layer's pmf is opacity x T / layer_totals exactly.
TEST(TransmittanceRecordLayers, FreeFlightMeetsEachLayerWithItsMass) {
  TransmittanceRecord r = make_record({{0.0f, 1.0f, RGB(0.5f), RGB(0.3f)}, {1.5f, 2.0f, RGB(1.0f), RGB(1.0f)}});
  r.insert_layers(std::vector<SurfaceLayer>{{0.5f, 0.3f, {}}, {1.2f, 0.6f, {}}, {1.8f, 0.5f, {}}});
  Pcg32 rng(7, 3);
  const int n = 400000;
  std::vector<int> met(3, 0);
  for (int i = 0; i < n; ++i) {
    const auto s = r.sample_free_flight(rng.next_float(), rng.next_float());
    if (s && s->layer >= 0) {
      ++met[size_t(s->layer)];
      EXPECT_FLOAT_EQ(s->t, r.layers()[size_t(s->layer)].t);
      EXPECT_FLOAT_EQ(s->pdf, r.layers()[size_t(s->layer)].before.r * r.layers()[size_t(s->layer)].opacity);
    }
  }
  for (size_t k = 0; k < 3; ++k) {
    const SurfaceLayer& l = r.layers()[k];
    const double p = double(l.before.r) * l.opacity;
    EXPECT_NEAR(double(met[k]) / n, p, 4.0 * std::sqrt(p * (1 - p) / n)) << "layer " << k;
  }
  float cumulative = 0.0f;
  for (size_t k = 0; k < 3; ++k) {
    const SurfaceLayer& l = r.layers()[k];
    const float pmf = l.before.r * l.opacity / r.layer_totals().r;
    const auto chosen = r.sample_layer(0, cumulative + 0.5f * pmf);
    ASSERT_TRUE(chosen);
    EXPECT_EQ(chosen->layer, int(k));
    EXPECT_NEAR(chosen->pdf, pmf, 1e-6f);
    cumulative += pmf;
  }
}

}  // namespace
}  // namespace caligo
