// The preview pipeline: linear scene-referred RGB -> 8-bit sRGB for a PNG someone looks at.
// It is for eyes only; the EXR stays the result of record and no metric reads the preview.
//
// Per channel, in this order:
//   1. exposure: multiply by 2^stops;
//   2. tone curve (filmic = true): the ACES filmic fit of Narkowicz 2015, "ACES Filmic Tone
//      Mapping Curve", f(x) = x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14), clamped to [0, 1].
//      We deviate from the post in two ways: no 0.6 pre-scale (use exposure_stops instead), and
//      negative input is clamped to 0 first (the fit is only meant for x >= 0). f(0) = 0; f is
//      increasing on x >= 0 and reaches 1 at x ~= 7.24, where the clamp saturates it.
//      It is applied to R, G, B separately, so very bright saturated colours drift towards
//      white: acceptable for a preview, and it is what the common real-time ports do.
//      filmic = false clamps to [0, 1] instead;
//   3. the sRGB OETF (IEC 61966-2-1, exact piecewise form, not a 2.2 gamma);
//   4. quantisation to 0..255 with round-to-nearest.
// Non-finite input (NaN, +-Inf) becomes 0, i.e. black, and is counted so callers can warn:
// a NaN in a render is a bug and must not hide as a plausible-looking pixel.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "image/image.h"

namespace caligo {

struct PreviewSettings {
  float exposure_stops = 0.0f;
  bool filmic = true;
};

// RGB bytes, 3 per pixel, rows top to bottom, read from the channels "R", "G", "B" (throws
// std::invalid_argument when any is missing). When non_finite_pixels is given it receives the
// number of pixels with at least one non-finite R, G or B value.
std::vector<uint8_t> to_srgb8_preview(const Image& image, const PreviewSettings& settings = {},
                                      size_t* non_finite_pixels = nullptr);

// The stages, exposed for tests and for anyone who needs one of them alone.
float exposure_scale(float stops);       // 2^stops
float aces_filmic(float x);              // step 2 above; [0, 1]
float srgb_oetf(float linear);           // linear [0, 1] -> encoded [0, 1]
uint8_t quantize_unorm8(float encoded);  // [0, 1] -> 0..255, rounded; clamps outside
// Steps 1-4 for one finite channel value.
uint8_t preview_channel(float linear, const PreviewSettings& settings);

}  // namespace caligo
