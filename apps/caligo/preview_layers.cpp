// What the preview page can show of a resolved image (preview_server.h), without httplib.
#include <algorithm>
#include <cmath>
#include <optional>
#include <set>

#include "core/median.h"
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

// The median of the finite depths, the scale the depth layer is shown at.
float median_depth(const Image& image, int z) {
  std::vector<double> finite;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x)
      if (std::isfinite(image.at(x, y, z)) && image.at(x, y, z) > 0.0f) finite.push_back(image.at(x, y, z));
  return finite.empty() ? 1.0f : std::max(float(median(std::move(finite))), 1e-6f);
}

}  // namespace

std::optional<Image> preview_layer(const Image& image, const std::string& layer) {
  if (layer == "beauty") {
    if (const auto ch = image.rgb_indices("")) return image.rgb_image(*ch);
    return std::nullopt;
  }
  if (layer == "N") {
    const int x = image.channel_index("N.X"), y = image.channel_index("N.Y"), z = image.channel_index("N.Z");
    if (x < 0 || y < 0 || z < 0) return std::nullopt;
    Image normals = image.rgb_image({x, y, z});
    for (float& v : normals.pixels()) v = 0.5f * v + 0.5f;  // [-1, 1] shown as [0, 1]
    return normals;
  }
  if (layer == "Z") {
    const int z = image.channel_index("Z");
    if (z < 0) return std::nullopt;
    // Near white, far dark: 1 / (1 + z / median of the finite depths); the background black.
    const float median = median_depth(image, z);
    return grey(image, z, [median](float v) { return std::isfinite(v) ? 1.0f / (1.0f + std::max(v, 0.0f) / median) : 0.0f; });
  }
  if (layer == "A") {
    const int a = image.channel_index("A");
    if (a < 0) return std::nullopt;
    return grey(image, a, [](float v) { return v; });
  }
  if (const auto ch = image.rgb_indices(layer + ".")) return image.rgb_image(*ch);
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
