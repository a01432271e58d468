#include "image/compare.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace caligo {

namespace {

std::string size_text(const Image& image) {
  return std::to_string(image.width()) + "x" + std::to_string(image.height());
}

std::array<int, 3> require_rgb(const Image& image, const char* which) {
  auto rgb = image.rgb_indices();
  if (!rgb) {
    throw std::invalid_argument(std::string("compare_images: the ") + which +
                                " image has no R, G and B channels");
  }
  return *rgb;
}

void check_comparable(const Image& a, const Image& b) {
  if (a.width() != b.width() || a.height() != b.height()) {
    throw std::invalid_argument("compare_images: image sizes differ (" + size_text(a) + " vs reference " +
                                size_text(b) + ")");
  }
}

// Running sums over every (pixel, channel) value; turned into means at the end.
struct Sums {
  double squared = 0, relative_squared = 0, a = 0, b = 0, max_abs = 0;

  void add(double va, double vb) {
    double diff = va - vb;
    squared += diff * diff;
    relative_squared += diff * diff / (vb * vb + 1e-2);
    a += va;
    b += vb;
    // std::max would drop a NaN that came second; once max_abs is NaN it stays NaN.
    double abs_diff = std::abs(diff);
    if (std::isnan(abs_diff) || abs_diff > max_abs) max_abs = abs_diff;
  }
};

}  // namespace

ImageMetrics compare_images(const Image& a, const Image& b) {
  check_comparable(a, b);
  const std::array<int, 3> ca = require_rgb(a, "first"), cb = require_rgb(b, "reference");
  Sums sums;
  for (int y = 0; y < a.height(); ++y) {
    for (int x = 0; x < a.width(); ++x) {
      for (int i = 0; i < 3; ++i) sums.add(a.at(x, y, ca[i]), b.at(x, y, cb[i]));
    }
  }
  ImageMetrics m;
  m.pixels = a.pixel_count();
  if (m.pixels == 0) return m;
  const double n = 3.0 * double(m.pixels);
  m.rmse = std::sqrt(sums.squared / n);
  m.relative_mse = sums.relative_squared / n;
  m.mean_difference = sums.a / n - sums.b / n;
  m.max_abs_difference = sums.max_abs;
  return m;
}

size_t non_finite_rgb(const Image& image) {
  const auto rgb = image.rgb_indices();
  if (!rgb) return 0;
  size_t n = 0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x)
      for (int c : *rgb) n += std::isfinite(image.at(x, y, c)) ? 0 : 1;
  return n;
}

}  // namespace caligo
