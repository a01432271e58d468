// 8-bit RGB PNG output for previews (see tonemap.h), written with libpng (two small shared
// libraries, libpng and zlib). Animated GIFs go through OpenImageIO in the caligo_oiio.so plugin
// (oiio_plugin.h), loaded only by runs that write one.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace caligo {

// Writes `rgb8` (3 bytes per pixel, rows top to bottom, as to_srgb8_preview returns) as a PNG,
// atomically: readers see the old file or the complete new one. Throws std::invalid_argument
// when the buffer does not hold width * height * 3 bytes, and std::runtime_error carrying
// libpng's message when writing fails; `path` is then untouched.
void write_png(const std::string& path, int width, int height, const std::vector<uint8_t>& rgb8);
// The same PNG in memory (the preview server's responses). Throws std::runtime_error on failure.
std::string encode_png(int width, int height, const std::vector<uint8_t>& rgb8);

// Writes an animated GIF (OpenImageIO's GIF writer, one subimage per frame, palette per
// frame), atomically like write_png. Every frame holds width * height * 3 bytes. Throws
// std::runtime_error when the plugin is missing or writing fails.
void write_gif(const std::string& path, int width, int height, const std::vector<std::vector<uint8_t>>& frames,
               float frames_per_second);

}  // namespace caligo
