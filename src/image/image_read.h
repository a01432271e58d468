// Reading pictures in any format OpenImageIO knows (PNG, JPEG, TIFF, EXR, HDR, ...) as linear
// RGB: gobo (cookie) textures for lights. OpenImageIO is reached through the caligo_oiio.so
// plugin (oiio_plugin.h), loaded on the first call: it costs ~0.2–0.45 s and ~100 MB (docs/benchmarks.md) of process
// start-up, which runs that read no image do not pay.
#pragma once

#include <string>

#include "image/image.h"

namespace caligo {

// The first subimage of `path` as an Image with channels R, G, B (rows top to bottom),
// in linear light: 8- and 16-bit integer files are sRGB-decoded unless the file says its
// colour space is linear; float files are taken as linear. One channel is grey (copied to
// R, G, B); two are grey + alpha; from four or more the first three are kept (alpha is
// ignored: a gobo filters light by colour, it is not composited).
// A missing, unreadable or oversized file throws caligo::InputError naming the file.
Image read_image_rgb(const std::string& path);

// The first subimage of `path` as a one-channel Image of data in [0, 1] (masks: opacity), read as
// stored, without sRGB decoding (Cycles' "Non-Color"): the alpha channel where the file has one
// (two or four or more channels), otherwise the grey value (one channel, or the mean of R, G, B).
// Errors as read_image_rgb.
Image read_image_grey(const std::string& path);

// The sRGB transfer function inverted (IEC 61966-2-1): encoded [0, 1] -> linear [0, 1].
float srgb_to_linear(float encoded);

}  // namespace caligo
