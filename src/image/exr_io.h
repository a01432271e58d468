// OpenEXR files in and out, through OpenEXR's own C++ API (not OpenImageIO, whose process
// start-up cost the unit tests should not pay). Every channel of the Image is written and read.
#pragma once

#include <string>
#include <vector>

#include "image/exr_attributes.h"
#include "image/image.h"

namespace caligo {

// Writes every channel of `image` as 32-bit FLOAT (or HALF when `half` is set: smaller, but only
// ~3 decimal digits and a maximum of 65504), ZIP-compressed, scanline. The file appears
// atomically: readers see the old file or the complete new one. `attributes` go in the header
// (exr_attributes.h). Throws std::invalid_argument for an empty image or an attribute OpenEXR
// sets itself, and std::runtime_error (naming the file) when the file cannot be written;
// `path` is then untouched and no temporary file is left behind.
void write_exr(const std::string& path, const Image& image, bool half = false, const ExrAttributes& attributes = {});

// Reads every channel of a scanline or tiled EXR (the first part of a multi-part file) as float,
// whatever its pixel type. The image covers the data window; its offset is not kept.
// On disk EXR sorts channels by name, so they are returned in the order a renderer writes them:
// the root layer first with R, G, B, A leading and its other channels (Z, ...) alphabetically
// after them, then each layer ("N.", "albedo.") in alphabetical order, again R, G, B, A first.
// A missing, unreadable or malformed file, or one that needs features we do not read
// (subsampled channels, deep data), throws caligo::InputError naming the file.
Image read_exr(const std::string& path);

// The header attributes of an EXR file (attributes_of), with read_exr's errors.
ExrAttributes read_exr_attributes(const std::string& path);

// The ordering rule above, exposed for tests: channel names sorted into read order.
std::vector<std::string> exr_channel_order(std::vector<std::string> names);

}  // namespace caligo
