// A feature-guided denoiser for Caligo's renders, after NFOR (Bitterli et al. 2016, "Nonlinearly
// Weighted First-order Regression for Denoising Monte Carlo Renderings"), written for this
// project from the paper:
//
// 1. Cross-filtering. Each half-sample image is filtered with weights computed from the other
//    half, so that a pixel's noise never decides its own weights (the bias NL-means has when it
//    reads the image it filters). The weights are NL-means weights between 3x3 patches of the
//    guide half, with the noise cancelled as Rousselle et al. 2012 do:
//      d^2(p, q) = mean over the patch and R, G, B of
//                  ((g(p) - g(q))^2 - (v(p) + min(v(p), v(q)))) / (eps + k^2 (v(p) + v(q)))
//      w(p, q)   = exp(-max(0, d^2)),
//    v the half's variance (twice the beauty's). In fog, where surface features say nothing,
//    these colour weights are what keep a shaft's edge and a shadow in the fog.
// 2. First-order regression. Within a (2r+1)^2 window, the filtered half is fitted by weighted
//    least squares as c(q) ~ a + b . (f(q) - f(p)) over the features f (albedo, normal, depth);
//    the estimate at p is a. A small ridge on b keeps flat features (constant albedo, the
//    background) from making the system singular. Edges of depth and normal are followed by
//    the linear term rather than blurred.
// 3. Selection. The two cross-filtered halves are averaged. Their error is estimated per pixel
//    from the other half (E[(o_a - h_b)^2] = MSE(o_a) + Var(h_b): the halves' noise is
//    independent), the input's error is its variance, both are averaged over a (2s+1)^2 box,
//    and each pixel takes the candidate of the lower estimate: the result is never worse than
//    the noisy input in that estimate.
//
// Cost: O(pixels x window x features^2), tiled and threaded; 2.0 s for 1920x1080 on two cores
// at the default window (docs/benchmarks.md, bench_denoise.cpp).
#pragma once

#include <vector>

#include "core/rgb.h"
#include "denoise/denoise_layers.h"

namespace caligo {

struct DenoiseSettings {
  int radius = 4;            // the regression window: (2 radius + 1)^2 pixels (4 measured best on default)
  float k = 0.45f;           // NL-means: larger accepts more dissimilar patches
  int selection_radius = 3;  // the box the error estimates are averaged over
};

struct DenoiseResult {
  std::vector<RGB> image;      // rows from the top
  std::vector<float> filtered;  // per pixel, 1 where the filtered candidate was taken, 0 the input
  // The estimated mean squared error (mean over pixels and R, G, B) of the noisy beauty and of
  // the result, from the half-buffer estimate above.
  double estimated_mse_input = 0, estimated_mse_output = 0;
};

DenoiseResult denoise(const DenoiseLayers& layers, const DenoiseSettings& settings = {});

// Step 1 and 2 alone, for tests: `y` filtered with weights from `guide` (variance
// `guide_variance`, of the guide half).
PixelPlanes3 cross_filter(const PixelPlanes3& y, const PixelPlanes3& guide, const PixelPlane& guide_variance, const DenoiseLayers& layers,
                     const DenoiseSettings& settings);

}  // namespace caligo
