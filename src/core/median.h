// The median of a sample (the mean of the two middle values for an even count; 0 when empty):
// how frame times are summarised, robust to the odd slow frame of a shared machine.
#pragma once

#include <algorithm>
#include <vector>

namespace caligo {

inline double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace caligo
