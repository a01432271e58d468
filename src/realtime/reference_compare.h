// Measuring a real-time frame against the path tracer's single-scattering reference, and
// the side-by-side picture `caligo realtime --compare-reference` writes:
// real-time | reference | error heat map with a scale bar.
#pragma once

#include <cstdint>
#include <vector>

#include "image/image.h"
#include "realtime/plane.h"

namespace caligo {

// An "R", "G", "B" image of the planes.
Image to_image(const ColorPlanes& planes);

//   mean_error     = (mean(a) - mean(ref)) / mean(ref)          signed: bias of the whole frame
//   relative_rmse  = sqrt(mean (a - ref)^2 / (ref^2 + 1e-2))    per pixel and channel: the root of
//                    image/compare.h's relative MSE (Rousselle et al. 2011), so dark regions and
//                    the bright core around a visible light weigh by their own brightness
//   rmse_over_mean = sqrt(mean (a - ref)^2) / mean(ref)         the absolute error against the
//                    frame's mean: dominated by the brightest pixels and by dark frames' noise
struct ReferenceError {
  double mean_error = 0;
  double relative_rmse = 0;
  double rmse_over_mean = 0;
};
ReferenceError reference_error(const Image& realtime, const Image& reference);

struct Rgb8Image {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;  // 3 bytes per pixel, rows top to bottom
};

// The three panels side by side, previews tone mapped with `exposure_stops`. The heat map
// shows |a - ref| (mean over channels) / (heat_scale x mean(ref)) through a black-red-yellow-white
// ramp; a bar under it shows the ramp from 0 to heat_scale, labelled with the scale in percent.
Rgb8Image comparison_strip(const Image& realtime, const Image& reference, float exposure_stops, float heat_scale);

}  // namespace caligo
