// Test-only: the running mean and standard error of one estimate, for checks "within k standard
// errors of the estimate's own sample".
#pragma once

#include <algorithm>
#include <cmath>

namespace caligo::testing {

struct Stat {
  double sum = 0, sum2 = 0;
  int n = 0;
  void add(double x) {
    sum += x;
    sum2 += x * x;
    ++n;
  }
  double mean() const { return sum / n; }
  double se() const { return std::sqrt(std::max(0.0, sum2 / n - mean() * mean()) / n); }
};

}  // namespace caligo::testing
