#include "layers.h"

#include <algorithm>
#include <map>

#include "core/error.h"
#include "core/message_text.h"

namespace caligo::python {
namespace {

const SourceLocation kArguments{"python", ""};

// The layer an EXR channel belongs to.
std::string layer_of(const std::string& channel) {
  const size_t dot = channel.rfind('.');
  if (dot == std::string::npos) {
    if (channel == "R" || channel == "G" || channel == "B") return "beauty";
    if (channel == "A") return "alpha";
    if (channel == "Z") return "depth";
    return channel;
  }
  const std::string prefix = channel.substr(0, dot);
  return prefix == "N" ? "normal" : prefix;
}

}  // namespace

std::vector<Layer> split_layers(const Image& image) {
  std::vector<Layer> layers;
  std::vector<std::vector<int>> sources;
  for (int c = 0; c < image.channel_count(); ++c) {
    const std::string name = layer_of(image.channels()[size_t(c)]);
    auto it = std::find_if(layers.begin(), layers.end(), [&](const Layer& l) { return l.name == name; });
    if (it == layers.end()) {
      layers.push_back({name, {}, image.width(), image.height(), {}});
      sources.emplace_back();
      it = layers.end() - 1;
    }
    it->channels.push_back(image.channels()[size_t(c)]);
    sources[size_t(it - layers.begin())].push_back(c);
  }
  const std::span<const float> all = image.pixels();
  const size_t stride = size_t(image.channel_count());
  for (size_t l = 0; l < layers.size(); ++l) {
    const std::vector<int>& from = sources[l];
    layers[l].pixels.resize(image.pixel_count() * from.size());
    float* out = layers[l].pixels.data();
    for (size_t p = 0; p < image.pixel_count(); ++p)
      for (const int c : from) *out++ = all[p * stride + size_t(c)];
  }
  return layers;
}

std::vector<std::string> channel_names(const std::string& name, int channels) {
  const auto refuse = [&](const std::string& expected) -> std::vector<std::string> {
    throw InputError(kArguments, "layer " + quote_for_message(name) + " has " + std::to_string(channels) +
                                     " channels; expected " + expected);
  };
  if (name.empty()) throw InputError(kArguments, "a layer needs a name");
  if (name == "beauty") {
    if (channels == 3) return {"R", "G", "B"};
    if (channels == 4) return {"R", "G", "B", "A"};
    return refuse("3 (RGB) or 4 (RGBA)");
  }
  if (name == "alpha") return channels == 1 ? std::vector<std::string>{"A"} : refuse("1");
  if (name == "depth") return channels == 1 ? std::vector<std::string>{"Z"} : refuse("1");
  if (name == "normal") return channels == 3 ? std::vector<std::string>{"N.X", "N.Y", "N.Z"} : refuse("3");
  if (channels == 1) return {name};
  if (channels == 3) return {name + ".R", name + ".G", name + ".B"};
  if (channels == 4) return {name + ".R", name + ".G", name + ".B", name + ".A"};
  return refuse("1, 3 or 4");
}

Image join_layers(const std::vector<Layer>& layers) {
  if (layers.empty()) throw InputError(kArguments, "no layers to write");
  std::vector<std::string> names;
  for (const Layer& l : layers) {
    if (l.width != layers[0].width || l.height != layers[0].height)
      throw InputError(kArguments, "layer " + quote_for_message(l.name) + " is " + std::to_string(l.width) + "x" +
                                       std::to_string(l.height) + ", layer " + quote_for_message(layers[0].name) +
                                       " " + std::to_string(layers[0].width) + "x" + std::to_string(layers[0].height) +
                                       "; every layer of an image has one size");
    for (const std::string& c : l.channels) {
      if (std::find(names.begin(), names.end(), c) != names.end())
        throw InputError(kArguments, "two layers write the channel " + quote_for_message(c));
      names.push_back(c);
    }
  }
  Image image(layers[0].width, layers[0].height, names);
  const std::span<float> all = image.pixels();
  const size_t stride = names.size();
  size_t first = 0;
  for (const Layer& l : layers) {
    const size_t n = l.channels.size();
    for (size_t p = 0; p < image.pixel_count(); ++p)
      for (size_t c = 0; c < n; ++c) all[p * stride + first + c] = l.pixels[p * n + c];
    first += n;
  }
  return image;
}

}  // namespace caligo::python
