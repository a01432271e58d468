#include "image/image_read.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "core/error.h"

namespace caligo {
namespace {

// Larger than any texture a light needs; stops a corrupt header from allocating gigabytes.
constexpr int64_t kMaxPixels = int64_t(16384) * 16384;

bool is_integer_format(OIIO::TypeDesc format) {
  return format.basetype != OIIO::TypeDesc::FLOAT && format.basetype != OIIO::TypeDesc::HALF &&
         format.basetype != OIIO::TypeDesc::DOUBLE;
}

bool says_linear(const OIIO::ImageSpec& spec) {
  std::string space = spec.get_string_attribute("oiio:ColorSpace");
  std::transform(space.begin(), space.end(), space.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return space.find("linear") != std::string::npos || space == "scene_linear";
}

}  // namespace

float srgb_to_linear(float v) { return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f); }

Image read_image_rgb(const std::string& path) {
  std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(path);
  if (!in) {
    std::string why = OIIO::geterror();
    if (why.empty()) why = "unknown format or unreadable file";
    throw InputError({path, ""}, "cannot read the image: " + why);
  }
  const OIIO::ImageSpec spec = in->spec();
  const int channels = spec.nchannels;
  if (spec.width <= 0 || spec.height <= 0 || channels <= 0 || int64_t(spec.width) * spec.height > kMaxPixels)
    throw InputError({path, ""}, "cannot read the image: unsupported size " + std::to_string(spec.width) +
                                     "x" + std::to_string(spec.height) + " with " + std::to_string(channels) +
                                     " channels");
  std::vector<float> data(size_t(spec.width) * size_t(spec.height) * size_t(channels));
  if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, data.data()))
    throw InputError({path, ""}, "cannot read the image: " + in->geterror());
  in->close();

  const bool decode = is_integer_format(spec.format) && !says_linear(spec);
  Image image(spec.width, spec.height, {"R", "G", "B"});
  for (size_t p = 0; p < image.pixel_count(); ++p) {
    const float* px = &data[p * size_t(channels)];
    for (int c = 0; c < 3; ++c) {
      float v = px[channels >= 3 ? c : 0];
      if (!std::isfinite(v)) throw InputError({path, ""}, "the image holds a non-finite value");
      v = std::max(0.0f, v);
      image.pixels()[p * 3 + size_t(c)] = decode ? srgb_to_linear(std::min(v, 1.0f)) : v;
    }
  }
  return image;
}

}  // namespace caligo
