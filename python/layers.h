// An Image's channels as the named arrays Python sees, and back: what `caligo.render` returns
// and `caligo.write_exr` takes. Plain C++ (no pybind11), so the naming is tested on its own
// terms and the heavy header stays in bindings.cpp.
//
// Names: the root R, G, B are "beauty", A "alpha", Z "depth", the N.X/Y/Z layer "normal";
// every other layer keeps its EXR name ("albedo", "volume_direct", "variance"), and a root
// channel of its own ("samples") is a layer of one channel.
#pragma once

#include <string>
#include <vector>

#include "image/image.h"

namespace caligo::python {

struct Layer {
  std::string name;
  std::vector<std::string> channels;  // the EXR channel names, in order
  int width = 0, height = 0;
  std::vector<float> pixels;  // row-major, channels interleaved (height x width x channels)
};

// The image's channels grouped into layers, in the image's channel order of first appearance.
std::vector<Layer> split_layers(const Image& image);

// The EXR channel names of a layer of `channels` channels called `name` (the inverse of
// split_layers): beauty 3 -> R G B (4 -> R G B A), alpha/depth 1 -> A / Z, normal 3 -> N.X..,
// another name with 1 -> "name", 3 -> name.R/G/B, 4 -> name.R/G/B/A. Throws InputError for
// counts that have no names (2 or more than 4, or beauty/normal not 3).
std::vector<std::string> channel_names(const std::string& name, int channels);

// One image of the layers (all of one size); InputError when sizes differ or names repeat.
Image join_layers(const std::vector<Layer>& layers);

}  // namespace caligo::python
