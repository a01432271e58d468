#include "image/image_read.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "image/oiio_plugin.h"

namespace caligo {
namespace {

// Larger than any texture a light needs; stops a corrupt header from allocating gigabytes.
constexpr int64_t kMaxPixels = int64_t(16384) * 16384;
// Far above any radiance (the sun's is ~1e9 W m^-2 sr^-1), far enough below float's 3.4e38 that
// the sums of a sampling distribution over 2^28 pixels stay finite.
constexpr float kMaxValue = 1e29f;

bool says_linear(std::string space) {
  std::transform(space.begin(), space.end(), space.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return space.find("linear") != std::string::npos || space == "scene_linear";
}

}  // namespace

float srgb_to_linear(float v) { return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f); }

namespace {

// The first subimage as stored, every value finite and at most kMaxValue.
OiioImage read_raw(const std::string& path) {
  OiioImage raw;
  std::string why;
  switch (oiio_plugin("needed to read images").read_image(path, kMaxPixels, &raw, &why)) {
    case OiioReadStatus::kOk:
      break;
    case OiioReadStatus::kCannotOpen:
      if (why.empty()) why = "unknown format or unreadable file";
      throw InputError({path, ""}, "cannot read the image: " + why);
    case OiioReadStatus::kBadSize:
      throw InputError({path, ""}, "cannot read the image: unsupported size " + std::to_string(raw.width) + "x" +
                                       std::to_string(raw.height) + " with " + std::to_string(raw.channels) +
                                       " channels");
    case OiioReadStatus::kCannotRead:
      throw InputError({path, ""}, "cannot read the image: " + why);
  }
  for (const float v : raw.pixels) {
    if (!std::isfinite(v)) throw InputError({path, ""}, "the image holds a non-finite value");
    if (v > kMaxValue)
      throw InputError({path, ""}, "the image holds the value " + std::to_string(v) + ", above the 1e29 allowed");
  }
  return raw;
}

}  // namespace

Image read_image_rgb(const std::string& path) {
  const OiioImage raw = read_raw(path);
  const int channels = raw.channels;
  const bool decode = raw.integer_format && !says_linear(raw.color_space);
  Image image(raw.width, raw.height, {"R", "G", "B"});
  for (size_t p = 0; p < image.pixel_count(); ++p) {
    const float* px = &raw.pixels[p * size_t(channels)];
    for (int c = 0; c < 3; ++c) {
      const float v = std::max(0.0f, px[channels >= 3 ? c : 0]);
      image.pixels()[p * 3 + size_t(c)] = decode ? srgb_to_linear(std::min(v, 1.0f)) : v;
    }
  }
  return image;
}

Image read_image_grey(const std::string& path) {
  const OiioImage raw = read_raw(path);
  const int channels = raw.channels;
  Image image(raw.width, raw.height, {"Y"});
  for (size_t p = 0; p < image.pixel_count(); ++p) {
    const float* px = &raw.pixels[p * size_t(channels)];
    float v = px[0];
    if (channels == 2) v = px[1];
    if (channels == 3) v = (px[0] + px[1] + px[2]) / 3.0f;
    if (channels >= 4) v = px[3];
    image.pixels()[p] = std::clamp(v, 0.0f, 1.0f);
  }
  return image;
}

}  // namespace caligo
