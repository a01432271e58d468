// What the denoiser reads from a Caligo EXR, as planes: the two half-sample images (`half_a`,
// `half_b`: the same pixels rendered from disjoint halves of the samples, whose mean is the
// beauty), the variance of the beauty's mean per pixel (`variance`), and the features the
// regression follows (albedo, normal, depth).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "image/image.h"

namespace caligo {

// Planar float images of one size; a plane is width * height values, rows from the top.
using PixelPlane = std::vector<float>;
using PixelPlanes3 = std::array<PixelPlane, 3>;

// Features of the regression, each scaled to unit spread over the image (denoise_layers).
inline constexpr int kDenoiseFeatures = 7;  // albedo R, G, B; normal X, Y, Z; depth

struct DenoiseLayers {
  int width = 0, height = 0;
  PixelPlanes3 half_a, half_b;
  PixelPlane variance;  // of the beauty's mean, averaged over R, G, B, lightly smoothed
  std::array<PixelPlane, kDenoiseFeatures> features;
};

// The layers denoise_layers needs, as channel-name prefixes.
inline constexpr std::array<const char*, 5> kDenoiseLayerNames = {"half_a.", "half_b.", "variance.", "albedo.", "N."};

// Reads them from `image` (and Z). A missing layer is an InputError at `where` naming it and the
// command that writes it; a non-finite value anywhere is one too.
DenoiseLayers denoise_layers(const Image& image, const std::string& where);

// The mean over a (2r+1)^2 box clamped to the image, separably.
PixelPlane box_mean(const PixelPlane& in, int w, int h, int r);

// `image` with the layer `name` (name.R, name.G, name.B) set to `values` (rows from the top):
// replaced where it exists, appended otherwise.
Image with_rgb_layer(const Image& image, const std::string& name, const std::vector<RGB>& values);

}  // namespace caligo
