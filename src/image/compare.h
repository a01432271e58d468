// Numbers that say how far a render is from a reference: used by the convergence and
// regression tests and by `caligo compare`. All metrics are over the R, G, B channels of every
// pixel (other channels are ignored), accumulated in double.
//
// The second image is the REFERENCE: relative_mse divides by it, and mean_difference is
// positive when the first image (the test render) is brighter.
//   rmse               = sqrt(mean (a - b)^2)
//   relative_mse       = mean (a - b)^2 / (b^2 + 1e-2)   the 1e-2 keeps black reference pixels
//                                                        from dominating (Rousselle et al. 2011)
//   mean_difference    = mean(a) - mean(b)               catches bias that noise would hide
//   max_abs_difference = max |a - b|
// A NaN or Inf in either image makes the metrics non-finite, on purpose: it must not pass a test.
// Two empty images compare as identical (all metrics 0, pixels 0).
#pragma once

#include <cstddef>

#include "image/image.h"

namespace caligo {

struct ImageMetrics {
  double rmse = 0;
  double relative_mse = 0;
  double mean_difference = 0;
  double max_abs_difference = 0;
  size_t pixels = 0;
};

// Throws std::invalid_argument naming the problem when the sizes differ or either image lacks
// an R, G or B channel.
ImageMetrics compare_images(const Image& a, const Image& b);

// How many of the image's R, G and B values are NaN or infinite (0 without those channels).
size_t non_finite_rgb(const Image& image);

}  // namespace caligo
