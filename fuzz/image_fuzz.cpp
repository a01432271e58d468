// Image files -> read_image_rgb (gobos and environment maps, through the OpenImageIO plugin),
// one target per extension so each corpus stays one format: an image that loads must be
// RGB with finite values in [0, 1e29] and a size its header could claim honestly.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "fuzz_support.h"
#include "image/image_read.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = caligo::fuzz::input_file(data, size, CALIGO_FUZZ_IMAGE_EXTENSION);
  caligo::fuzz::expect_value_or_input_error([&] {
    const caligo::Image image = caligo::read_image_rgb(path);
    if (image.channel_count() != 3 || image.width() < 1 || image.height() < 1) std::abort();
    for (float v : image.pixels())
      if (!(std::isfinite(v) && v >= 0.0f && v <= 1e29f)) std::abort();
  });
  return 0;
}
