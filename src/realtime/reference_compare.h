// Measuring a real-time frame against the path tracer's single-scattering reference, and
// the side-by-side picture `caligo realtime --compare-reference` writes:
// real-time | reference | error heat map with a scale bar.
#pragma once

#include <cstdint>
#include <vector>

#include "image/image.h"
#include "lights/light.h"
#include "realtime/light_cores.h"
#include "realtime/plane.h"
#include "realtime/view.h"

namespace caligo {

// An "R", "G", "B" image of the planes.
Image to_image(const ColorPlanes& planes);

//   mean_error     = (mean(a) - mean(ref)) / mean(ref)          signed: bias of the whole frame
//   relative_rmse  = sqrt(mean (a - ref)^2 / (ref^2 + 1e-2))    per pixel and channel: the root of
//                    image/compare.h's relative MSE (Rousselle et al. 2011), so dark regions and
//                    the bright core around a visible light weigh by their own brightness
//   rmse_over_mean = sqrt(mean (a - ref)^2) / mean(ref)         the absolute error against the
//                    frame's mean: dominated by the brightest pixels and by dark frames' noise
//
// With a mask of light cores (light_core_mask), the error users see is split in two:
//   outside_rmse_over_mean = rmse_over_mean over the pixels outside the cores (against their mean)
//   core_mean_error        = (sum(a) - sum(ref)) / sum(ref) over the core pixels: how much of the
//                            cores' light the frame keeps (a blurred core loses its peak, a
//                            noisy one gains or loses it)
// And where light leaks (through a wall, across an edge): over the pixels the reference leaves
// dark (below 1 % of its mean; a room's unlit fog and walls are exactly 0 there),
//   dark_fraction = their share of the pixels, dark_share = their share of the real-time
//                   frame's light (sum over them / sum over the frame)
struct ReferenceError {
  double mean_error = 0;
  double relative_rmse = 0;
  double rmse_over_mean = 0;
  double outside_rmse_over_mean = 0;  // = rmse_over_mean without a mask
  double core_mean_error = 0;         // 0 without a mask or without core pixels
  double core_fraction = 0;           // of the pixels
  double dark_fraction = 0, dark_share = 0;
};
ReferenceError reference_error(const Image& realtime, const Image& reference,
                               const std::vector<uint8_t>* cores = nullptr);

// The light cores of a view: 1 for pixels within `radius` pixels of where a light with a centre
// (light_centre: point lights, spot apexes, area lights) projects in front of the camera. There
// single scattering rises as 1/D for rays passing at distance D from the light, a peak narrower
// than an accumulation pixel: the real-time frame, marched at pixel centres at a fraction of the
// resolution and upsampled, cannot follow it, and the peak dominates any RMSE over the frame.
std::vector<uint8_t> light_core_mask(const std::vector<Light>& lights, const View& view, float radius);

struct Rgb8Image {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;  // 3 bytes per pixel, rows top to bottom
};

// The three panels side by side, previews tone mapped with `exposure_stops`. The heat map
// shows |a - ref| (mean over channels) / (heat_scale x mean(ref)) through a black-red-yellow-white
// ramp; a bar under it shows the ramp from 0 to heat_scale, labelled with the scale in percent.
Rgb8Image comparison_strip(const Image& realtime, const Image& reference, float exposure_stops, float heat_scale);

}  // namespace caligo
