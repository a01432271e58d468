// The denoiser as `caligo denoise` and `caligo render --denoise` use it (denoise_command.cpp).
#pragma once

#include <string>

#include "denoise/denoise.h"
#include "image/image.h"

namespace caligo {

struct DenoisedImage {
  Image image;  // the input's channels and denoised.R, .G, .B
  DenoiseResult result;
  double seconds = 0;
};

// Throws InputError at `where` when a layer the denoiser reads is missing.
DenoisedImage denoise_image(const Image& image, const std::string& where, const DenoiseSettings& settings = {});
// The denoised layer as a beauty (R, G, B): what the PNG preview shows.
Image denoised_beauty(const Image& image);
void print_denoise_summary(const DenoisedImage& d, const std::string& output);

}  // namespace caligo
