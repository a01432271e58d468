// A float image with named channels: what the film hands to the EXR writer, the preview tone
// mapper and the image comparison. A plain value type: copy it, move it, compare it with ==.
//
// Channel names follow OpenEXR's conventions: "R", "G", "B", "A", "Z" in the root layer and
// "<layer>.<channel>" for the rest ("N.X", "albedo.R"). Names must be non-empty and unique.
//
// Layout: row-major, origin at the top-left pixel, channels INTERLEAVED (all channels of one
// pixel are adjacent). Why interleaved rather than planar: the film writes every channel of a
// pixel at once and the tone mapper and comparison read R, G, B of one pixel together, so each
// touches one cache line instead of one per channel; OpenEXR's frame buffer takes strides, so
// the file border reads and writes this layout in place and planar would buy nothing there.
//
// Thread safety: like std::vector. Concurrent writes to different pixels are safe.
#pragma once

#include <array>
#include <cassert>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/rgb.h"

namespace caligo {

class Image {
 public:
  Image() = default;
  // A zero-filled width x height image. Throws std::invalid_argument for a negative size, an
  // empty channel name or a repeated one (an EXR file cannot hold two channels of one name).
  Image(int width, int height, std::vector<std::string> channels);

  int width() const { return width_; }
  int height() const { return height_; }
  size_t pixel_count() const { return size_t(width_) * size_t(height_); }
  int channel_count() const { return int(channels_.size()); }
  const std::vector<std::string>& channels() const { return channels_; }

  // Index of the named channel in channels(), or -1 when the image has none of that name.
  int channel_index(std::string_view name) const;
  bool has_channel(std::string_view name) const { return channel_index(name) >= 0; }

  // Indices of <prefix>R, <prefix>G, <prefix>B wherever they sit ("" for the beauty image,
  // "albedo." for an AOV layer); nullopt when any of the three is missing.
  std::optional<std::array<int, 3>> rgb_indices(std::string_view prefix = "") const;

  // Unchecked in release builds (assert only): these sit in the film's inner loop.
  float& at(int x, int y, int channel) { return pixels_[offset(x, y, channel)]; }
  float at(int x, int y, int channel) const { return pixels_[offset(x, y, channel)]; }

  // The three channels base, base + 1, base + 2 as an RGB (the usual R,G,B or layer.R,G,B run).
  RGB rgb(int x, int y, int base_channel) const;
  void set_rgb(int x, int y, int base_channel, RGB value);
  // The same for three channels that need not be adjacent (see rgb_indices).
  RGB rgb(int x, int y, const std::array<int, 3>& channels) const;
  // Those three channels as an image of its own, channels R, G, B (a layer shown as a beauty).
  Image rgb_image(const std::array<int, 3>& channels) const;

  // Every sample, interleaved as described above: pixel_count() * channel_count() floats.
  std::span<float> pixels() { return pixels_; }
  std::span<const float> pixels() const { return pixels_; }

  friend bool operator==(const Image&, const Image&) = default;

 private:
  size_t offset(int x, int y, int channel) const {
    assert(x >= 0 && x < width_ && y >= 0 && y < height_ && channel >= 0 && channel < channel_count());
    return (size_t(y) * size_t(width_) + size_t(x)) * channels_.size() + size_t(channel);
  }

  int width_ = 0;
  int height_ = 0;
  std::vector<std::string> channels_;
  std::vector<float> pixels_;
};

}  // namespace caligo
