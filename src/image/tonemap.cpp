#include "image/tonemap.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace caligo {

float exposure_scale(float stops) { return std::exp2(stops); }

float aces_filmic(float x) {
  // Coefficients as published by Narkowicz (2015).
  constexpr float a = 2.51f, b = 0.03f, c = 2.43f, d = 0.59f, e = 0.14f;
  if (!(x > 0.0f)) return 0.0f;  // negative and NaN input
  // f has reached 1 by x ~= 7.24; stopping at 16 keeps Inf from making Inf / Inf = NaN.
  x = std::min(x, 16.0f);
  return std::min(x * (a * x + b) / (x * (c * x + d) + e), 1.0f);
}

float srgb_oetf(float linear) {
  // The linear segment below 0.0031308 avoids the infinite slope of a pure power law at 0.
  if (linear <= 0.0031308f) return 12.92f * linear;
  return 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

uint8_t quantize_unorm8(float encoded) {
  if (!(encoded > 0.0f)) return 0;  // also NaN, which std::clamp would pass through
  return uint8_t(std::lround(std::clamp(encoded, 0.0f, 1.0f) * 255.0f));
}

uint8_t preview_channel(float linear, const PreviewSettings& settings) {
  float exposed = linear * exposure_scale(settings.exposure_stops);
  float display = settings.filmic ? aces_filmic(exposed) : std::clamp(exposed, 0.0f, 1.0f);
  return quantize_unorm8(srgb_oetf(display));
}

namespace {

std::array<int, 3> require_rgb(const Image& image) {
  auto rgb = image.rgb_indices();
  if (!rgb) throw std::invalid_argument("to_srgb8_preview: the image has no R, G and B channels");
  return *rgb;
}

}  // namespace

std::vector<uint8_t> to_srgb8_preview(const Image& image, const PreviewSettings& settings,
                                      size_t* non_finite_pixels) {
  const std::array<int, 3> channels = require_rgb(image);
  std::vector<uint8_t> out;
  out.reserve(image.pixel_count() * 3);
  size_t non_finite = 0;
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      bool finite = true;
      for (int c : channels) {
        float v = image.at(x, y, c);
        finite = finite && std::isfinite(v);
        out.push_back(std::isfinite(v) ? preview_channel(v, settings) : uint8_t(0));
      }
      non_finite += finite ? 0 : 1;
    }
  }
  if (non_finite_pixels) *non_finite_pixels = non_finite;
  return out;
}

}  // namespace caligo
