#include "materials/opacity_map.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace caligo {
namespace {

// x mod n in [0, n) for negative x too.
int wrap(int x, int n) {
  const int r = x % n;
  return r < 0 ? r + n : r;
}

}  // namespace

OpacityMap::OpacityMap(int width, int height, std::vector<float> values)
    : width_(width), height_(height), values_(std::move(values)) {
  if (width <= 0 || height <= 0 || values_.size() != size_t(width) * size_t(height))
    throw std::invalid_argument("OpacityMap: size does not match its values");
  for (float& v : values_) v = std::isfinite(v) ? std::clamp(v, 0.0f, 1.0f) : 0.0f;
}

float OpacityMap::texel(int x, int y) const {
  return values_[size_t(wrap(y, height_)) * size_t(width_) + size_t(wrap(x, width_))];
}

float OpacityMap::lookup(Vec2 uv) const {
  if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) return 1.0f;
  // Texel centres at (i + 1/2) / size; row 0 is the top (v = 1).
  const double fx = (double(uv.x) - std::floor(double(uv.x))) * width_ - 0.5;
  const double fy = (1.0 - (double(uv.y) - std::floor(double(uv.y)))) * height_ - 0.5;
  const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
  const float ax = float(fx - x0), ay = float(fy - y0);
  const float top = texel(x0, y0) * (1.0f - ax) + texel(x0 + 1, y0) * ax;
  const float bottom = texel(x0, y0 + 1) * (1.0f - ax) + texel(x0 + 1, y0 + 1) * ax;
  return top * (1.0f - ay) + bottom * ay;
}

}  // namespace caligo
