#include "render/pixel_filter.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace caligo {
namespace {

double blackman_harris_1d(double x, double r) {
  const double a = kPi * x / r;  // cos(2 pi (x / 2r + 1/2) k) = (-1)^k cos(k pi x / r)
  return 0.35875 + 0.48829 * std::cos(a) + 0.14128 * std::cos(2.0 * a) + 0.01168 * std::cos(3.0 * a);
}

double filter_1d(const PixelFilterDesc& d, double x) {
  if (!(std::abs(x) <= d.radius)) return 0.0;
  switch (d.type) {
    case PixelFilterType::box:
      return 1.0;
    case PixelFilterType::gaussian: {
      const double s2 = 2.0 * double(d.sigma) * double(d.sigma);
      return std::max(0.0, std::exp(-x * x / s2) - std::exp(-double(d.radius) * double(d.radius) / s2));
    }
    case PixelFilterType::blackman_harris:
      return std::max(0.0, blackman_harris_1d(x, d.radius));
  }
  return 0.0;
}

// Bin masses by composite Simpson's rule (8 intervals per bin), accumulated in double.
std::vector<float> tabulate_cdf(const PixelFilterDesc& d) {
  const int n = PixelFilter::kTableSize;
  const double r = d.radius, dx = 2.0 * r / n;
  std::vector<double> sums(size_t(n) + 1, 0.0);
  for (int i = 0; i < n; ++i) {
    const double x0 = -r + i * dx, h = dx / 8.0;
    double s = filter_1d(d, x0) + filter_1d(d, x0 + dx);
    for (int k = 1; k < 8; ++k) s += (k % 2 ? 4.0 : 2.0) * filter_1d(d, x0 + k * h);
    sums[size_t(i) + 1] = sums[size_t(i)] + s * h / 3.0;
  }
  std::vector<float> cdf(sums.size());
  for (size_t i = 0; i < sums.size(); ++i) cdf[i] = float(sums[i] / sums.back());
  cdf.back() = 1.0f;
  return cdf;
}

}  // namespace

PixelFilter::PixelFilter(const PixelFilterDesc& desc) : desc_(desc) {
  if (!(desc.radius > 0.0f && desc.radius <= 16.0f))
    throw std::invalid_argument("PixelFilter: radius must be in (0, 16] pixels");
  if (desc.type == PixelFilterType::gaussian && !(desc.sigma > 0.0f && std::isfinite(desc.sigma)))
    throw std::invalid_argument("PixelFilter: sigma must be > 0");
  if (desc.type != PixelFilterType::box) cdf_ = tabulate_cdf(desc);
}

PixelFilter PixelFilter::box(float radius) { return PixelFilter({PixelFilterType::box, radius, 0.5f}); }
PixelFilter PixelFilter::gaussian(float radius, float sigma) {
  return PixelFilter({PixelFilterType::gaussian, radius, sigma});
}
PixelFilter PixelFilter::blackman_harris(float radius) {
  return PixelFilter({PixelFilterType::blackman_harris, radius, 0.5f});
}

float PixelFilter::evaluate_1d(float x) const { return float(filter_1d(desc_, x)); }

float PixelFilter::pdf_1d(float x) const {
  const float r = desc_.radius;
  if (!(std::abs(x) <= r)) return 0.0f;
  if (cdf_.empty()) return 0.5f / r;
  const int n = kTableSize;
  const int i = std::clamp(int((x + r) / (2.0f * r) * float(n)), 0, n - 1);
  return (cdf_[size_t(i) + 1] - cdf_[size_t(i)]) * float(n) / (2.0f * r);
}

float PixelFilter::sample_1d(float u) const {
  const float r = desc_.radius;
  if (cdf_.empty()) return (2.0f * u - 1.0f) * r;
  const int n = kTableSize;
  // The bin i with cdf[i] <= u < cdf[i + 1]: never an empty bin.
  const auto it = std::upper_bound(cdf_.begin(), cdf_.end(), u);
  const int i = std::clamp(int(it - cdf_.begin()) - 1, 0, n - 1);
  const float mass = cdf_[size_t(i) + 1] - cdf_[size_t(i)];
  const float t = mass > 0.0f ? std::clamp((u - cdf_[size_t(i)]) / mass, 0.0f, 1.0f) : 0.5f;
  return std::clamp(-r + (float(i) + t) * (2.0f * r / float(n)), -r, r);
}

std::optional<PixelFilterType> pixel_filter_type_from_name(std::string_view name) {
  return enum_from_name(kPixelFilterNames, name);
}

const char* pixel_filter_name(PixelFilterType type) { return enum_name(kPixelFilterNames, type).data(); }

}  // namespace caligo
