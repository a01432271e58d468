// What the preview page can show of a resolved image (preview_server.h), without httplib.
#include <algorithm>
#include <cmath>
#include <optional>
#include <set>

#include "preview_server.h"

namespace caligo {
namespace {

Image grey(const Image& image, int channel, const std::function<float(float)>& map) {
  Image out(image.width(), image.height(), {"R", "G", "B"});
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      const float v = map(image.at(x, y, channel));
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = v;
    }
  return out;
}

Image rgb_of(const Image& image, const std::array<int, 3>& ch, float scale, float offset) {
  Image out(image.width(), image.height(), {"R", "G", "B"});
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x)
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = image.at(x, y, ch[size_t(c)]) * scale + offset;
  return out;
}

}  // namespace

std::optional<Image> preview_layer(const Image& image, const std::string& layer) {
  if (layer == "beauty") {
    if (const auto ch = image.rgb_indices("")) return rgb_of(image, *ch, 1.0f, 0.0f);
    return std::nullopt;
  }
  if (layer == "N") {
    const int x = image.channel_index("N.X"), y = image.channel_index("N.Y"), z = image.channel_index("N.Z");
    if (x < 0 || y < 0 || z < 0) return std::nullopt;
    return rgb_of(image, {x, y, z}, 0.5f, 0.5f);  // [-1, 1] shown as [0, 1]
  }
  if (layer == "Z") {
    const int z = image.channel_index("Z");
    if (z < 0) return std::nullopt;
    // Near white, far dark: 1 / (1 + z / median of the finite depths); the background black.
    std::vector<float> finite;
    for (int y = 0; y < image.height(); ++y)
      for (int x = 0; x < image.width(); ++x)
        if (std::isfinite(image.at(x, y, z))) finite.push_back(image.at(x, y, z));
    float median = 1.0f;
    if (!finite.empty()) {
      std::nth_element(finite.begin(), finite.begin() + std::ptrdiff_t(finite.size() / 2), finite.end());
      median = std::max(finite[finite.size() / 2], 1e-6f);
    }
    return grey(image, z, [median](float v) { return std::isfinite(v) ? 1.0f / (1.0f + std::max(v, 0.0f) / median) : 0.0f; });
  }
  if (layer == "A") {
    const int a = image.channel_index("A");
    if (a < 0) return std::nullopt;
    return grey(image, a, [](float v) { return v; });
  }
  if (const auto ch = image.rgb_indices(layer + ".")) return rgb_of(image, *ch, 1.0f, 0.0f);
  return std::nullopt;
}

std::vector<std::string> preview_layers(const Image& image) {
  std::vector<std::string> out;
  if (image.rgb_indices("")) out.push_back("beauty");
  if (image.rgb_indices("denoised.")) out.push_back("denoised");
  std::set<std::string> seen;
  for (const std::string& name : image.channels()) {
    const size_t dot = name.rfind('.');
    if (dot == std::string::npos) continue;
    const std::string prefix = name.substr(0, dot);
    if (prefix == "denoised" || !seen.insert(prefix).second) continue;
    if (prefix == "N" ? image.has_channel("N.X") : image.rgb_indices(prefix + ".").has_value()) out.push_back(prefix);
  }
  if (image.has_channel("Z")) out.push_back("Z");
  if (image.has_channel("A")) out.push_back("A");
  return out;
}

}  // namespace caligo
