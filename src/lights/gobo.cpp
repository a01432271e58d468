#include "lights/gobo.h"

#include <cmath>
#include <stdexcept>

namespace caligo {
namespace {

int wrap(int i, int n) {
  const int m = i % n;
  return m < 0 ? m + n : m;
}

}  // namespace

GoboImage::GoboImage(int width, int height, std::vector<RGB> pixels)
    : width_(width), height_(height), pixels_(std::move(pixels)) {
  if (width <= 0 || height <= 0 || pixels_.size() != static_cast<size_t>(width) * height)
    throw std::invalid_argument("GoboImage: size does not match the pixel count");
  RGB sum;
  for (const RGB& p : pixels_) sum += p;
  mean_ = sum / static_cast<float>(pixels_.size());
}

RGB GoboImage::lookup(Vec2 uv) const {
  // Pixel centres sit at (i + 0.5) / n; flip v so that v = 0 is the picture's bottom row.
  const float x = uv.x * width_ - 0.5f;
  const float y = (1.0f - uv.y) * height_ - 0.5f;
  if (!std::isfinite(x) || !std::isfinite(y)) return RGB(0.0f);
  const float fx = std::floor(x), fy = std::floor(y);
  const float tx = x - fx, ty = y - fy;
  // Reduce before converting so huge coordinates (long scrolls) cannot overflow an int.
  const int x0 = wrap(static_cast<int>(std::fmod(fx, static_cast<float>(width_))), width_);
  const int y0 = wrap(static_cast<int>(std::fmod(fy, static_cast<float>(height_))), height_);
  const int x1 = wrap(x0 + 1, width_), y1 = wrap(y0 + 1, height_);
  const RGB top = pixel(x0, y0) * (1.0f - tx) + pixel(x1, y0) * tx;
  const RGB bottom = pixel(x0, y1) * (1.0f - tx) + pixel(x1, y1) * tx;
  return top * (1.0f - ty) + bottom * ty;
}

}  // namespace caligo
