#include "image/image.h"

#include <algorithm>
#include <stdexcept>
#include <unordered_set>

namespace caligo {

namespace {

void check_channel_names(const std::vector<std::string>& channels) {
  std::unordered_set<std::string_view> seen;
  for (const std::string& name : channels) {
    if (name.empty()) throw std::invalid_argument("Image: empty channel name");
    if (!seen.insert(name).second) throw std::invalid_argument("Image: channel \"" + name + "\" given twice");
  }
}

}  // namespace

Image::Image(int width, int height, std::vector<std::string> channels)
    : width_(width), height_(height), channels_(std::move(channels)) {
  if (width < 0 || height < 0) {
    throw std::invalid_argument("Image: negative size " + std::to_string(width) + "x" +
                                std::to_string(height));
  }
  check_channel_names(channels_);
  pixels_.assign(pixel_count() * channels_.size(), 0.0f);
}

int Image::channel_index(std::string_view name) const {
  auto it = std::find(channels_.begin(), channels_.end(), name);
  return it == channels_.end() ? -1 : int(it - channels_.begin());
}

std::optional<std::array<int, 3>> Image::rgb_indices(std::string_view prefix) const {
  std::array<int, 3> indices{};
  const char* suffixes[3] = {"R", "G", "B"};
  for (int i = 0; i < 3; ++i) {
    indices[i] = channel_index(std::string(prefix) + suffixes[i]);
    if (indices[i] < 0) return std::nullopt;
  }
  return indices;
}

Image Image::rgb_image(const std::array<int, 3>& channels) const {
  Image out(width_, height_, {"R", "G", "B"});
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) out.set_rgb(x, y, 0, rgb(x, y, channels));
  return out;
}

RGB Image::rgb(int x, int y, int base_channel) const {
  const float* p = &pixels_[offset(x, y, base_channel)];
  assert(base_channel + 2 < channel_count());
  return {p[0], p[1], p[2]};
}

void Image::set_rgb(int x, int y, int base_channel, RGB value) {
  float* p = &pixels_[offset(x, y, base_channel)];
  assert(base_channel + 2 < channel_count());
  p[0] = value.r;
  p[1] = value.g;
  p[2] = value.b;
}

RGB Image::rgb(int x, int y, const std::array<int, 3>& channels) const {
  return {at(x, y, channels[0]), at(x, y, channels[1]), at(x, y, channels[2])};
}

}  // namespace caligo
