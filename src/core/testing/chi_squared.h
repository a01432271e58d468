// Chi-squared goodness-of-fit helpers shared by the statistical tests (sampling triads,
// phase functions, equiangular sampling, transmittance-record sampling). Test-only: nothing
// in the product includes it.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace caligo::test_stats {

// Regularised upper incomplete gamma function Q(a, x): a power series for P = 1 - Q when x < a + 1,
// otherwise a continued fraction for Q evaluated with the modified Lentz method.
inline double gamma_q(double a, double x) {
  if (x <= 0.0) return 1.0;
  const double log_prefactor = -x + a * std::log(x) - std::lgamma(a);
  if (x < a + 1.0) {
    double term = 1.0 / a, sum = term;
    for (int n = 1; n < 10000 && std::abs(term) > 1e-15 * std::abs(sum); ++n) {
      term *= x / (a + n);
      sum += term;
    }
    return std::max(0.0, 1.0 - sum * std::exp(log_prefactor));
  }
  const double tiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 10000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    h *= d * c;
    if (std::abs(d * c - 1.0) < 1e-15) break;
  }
  return std::exp(log_prefactor) * h;
}

// P(X >= chi2) for X ~ chi-squared with `dof` degrees of freedom.
inline double chi2_survival(double chi2, int dof) { return gamma_q(0.5 * dof, 0.5 * chi2); }

// Pearson's test. Bins expected to hold fewer than 5 samples are pooled (the chi-squared
// approximation needs reasonably large expected counts); a sample in a bin of zero expectation
// fails outright.
inline double chi2_p_value(const std::vector<double>& observed, const std::vector<double>& expected) {
  double chi2 = 0.0, pooled_observed = 0.0, pooled_expected = 0.0;
  int bins = 0;
  for (size_t i = 0; i < observed.size(); ++i) {
    if (expected[i] <= 0.0 && observed[i] > 0.0) return 0.0;
    if (expected[i] < 5.0) {
      pooled_observed += observed[i];
      pooled_expected += expected[i];
      continue;
    }
    chi2 += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
    ++bins;
  }
  if (pooled_expected > 0.0) {
    chi2 += (pooled_observed - pooled_expected) * (pooled_observed - pooled_expected) / pooled_expected;
    ++bins;
  }
  return bins > 1 ? chi2_survival(chi2, bins - 1) : 1.0;
}

}  // namespace caligo::test_stats
