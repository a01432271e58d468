#include "denoise/denoise_layers.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>

#include "core/error.h"
#include "core/median.h"

namespace caligo {
namespace {

std::array<int, 3> channels_of(const Image& image, const std::string& where, const std::string& prefix,
                               const std::array<const char*, 3>& names) {
  std::array<int, 3> out{};
  for (int c = 0; c < 3; ++c) {
    out[size_t(c)] = image.channel_index(prefix + names[size_t(c)]);
    if (out[size_t(c)] < 0)
      throw InputError(SourceLocation{where, ""},
                       "the denoiser needs the layer \"" + prefix.substr(0, prefix.size() - 1) + "\" (" + prefix +
                           names[size_t(c)] + " is missing); `caligo render --denoise` writes every layer it reads");
  }
  return out;
}

PixelPlanes3 planes_of(const Image& image, const std::array<int, 3>& ch) {
  PixelPlanes3 out;
  for (int c = 0; c < 3; ++c) {
    out[size_t(c)].resize(image.pixel_count());
    for (int y = 0; y < image.height(); ++y)
      for (int x = 0; x < image.width(); ++x)
        out[size_t(c)][size_t(y) * size_t(image.width()) + size_t(x)] = image.at(x, y, ch[size_t(c)]);
  }
  return out;
}

// Scales a feature to unit spread (its standard deviation, at least 1e-2 of its range's floor)
// so that the regression's ridge weighs every feature alike.
void normalise(PixelPlane& f) {
  double sum = 0, sum2 = 0;
  for (float v : f) sum += v, sum2 += double(v) * v;
  const double n = double(f.size());
  const double sd = std::sqrt(std::max(0.0, sum2 / n - (sum / n) * (sum / n)));
  const float scale = float(1.0 / std::max(sd, 1e-2));
  for (float& v : f) v *= scale;
}

}  // namespace

// Mean over a (2r+1)^2 box clamped to the image, separably.
PixelPlane box_mean(const PixelPlane& in, int w, int h, int r) {
  PixelPlane rows(in.size()), out(in.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float sum = 0.0f;
      const int a = std::max(0, x - r), b = std::min(w - 1, x + r);
      for (int i = a; i <= b; ++i) sum += in[size_t(y) * size_t(w) + size_t(i)];
      rows[size_t(y) * size_t(w) + size_t(x)] = sum / float(b - a + 1);
    }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float sum = 0.0f;
      const int a = std::max(0, y - r), b = std::min(h - 1, y + r);
      for (int j = a; j <= b; ++j) sum += rows[size_t(j) * size_t(w) + size_t(x)];
      out[size_t(y) * size_t(w) + size_t(x)] = sum / float(b - a + 1);
    }
  return out;
}

DenoiseLayers denoise_layers(const Image& image, const std::string& where) {
  if (image.pixel_count() == 0) throw InputError(SourceLocation{where, ""}, "the image is empty");
  DenoiseLayers d;
  d.width = image.width();
  d.height = image.height();
  const std::array<const char*, 3> rgb = {"R", "G", "B"}, xyz = {"X", "Y", "Z"};
  d.half_a = planes_of(image, channels_of(image, where, "half_a.", rgb));
  d.half_b = planes_of(image, channels_of(image, where, "half_b.", rgb));
  const PixelPlanes3 variance = planes_of(image, channels_of(image, where, "variance.", rgb));
  const PixelPlanes3 albedo = planes_of(image, channels_of(image, where, "albedo.", rgb));
  const PixelPlanes3 normal = planes_of(image, channels_of(image, where, "N.", xyz));
  const int z = image.channel_index("Z");
  if (z < 0) throw InputError(SourceLocation{where, ""}, "the denoiser needs the depth channel Z");
  for (const PixelPlanes3* planes : std::initializer_list<const PixelPlanes3*>{&d.half_a, &d.half_b, &variance, &albedo, &normal})
    for (const PixelPlane& plane : *planes)
      for (float v : plane)
        if (!std::isfinite(v)) throw InputError(SourceLocation{where, ""}, "a layer the denoiser reads holds a NaN or inf");
  PixelPlane avg(image.pixel_count());
  for (size_t i = 0; i < avg.size(); ++i) avg[i] = (variance[0][i] + variance[1][i] + variance[2][i]) / 3.0f;
  d.variance = box_mean(avg, d.width, d.height, 1);  // a pixel's own variance estimate is itself noisy
  for (int c = 0; c < 3; ++c) {
    d.features[size_t(c)] = albedo[size_t(c)];
    d.features[size_t(3 + c)] = normal[size_t(c)];
  }
  // Depth as z / (z + median): bounded, +inf (the background) at 1, resolution where the scene is.
  PixelPlane depth = planes_of(image, {z, z, z})[0];  // +inf is the background
  for (float v : depth)
    if (std::isnan(v) || v == -INFINITY) throw InputError(SourceLocation{where, ""}, "Z holds a NaN or -inf");
  std::vector<double> finite;
  for (float v : depth)
    if (std::isfinite(v) && v > 0.0f) finite.push_back(v);
  const float median_depth = finite.empty() ? 1.0f : std::max(float(median(std::move(finite))), 1e-6f);
  for (float& v : depth) v = std::isfinite(v) ? std::max(v, 0.0f) / (std::max(v, 0.0f) + median_depth) : 1.0f;
  d.features[6] = std::move(depth);
  for (PixelPlane& f : d.features) normalise(f);
  return d;
}

Image with_rgb_layer(const Image& image, const std::string& name, const std::vector<RGB>& values) {
  std::vector<std::string> channels = image.channels();
  for (const char* c : {"R", "G", "B"})
    if (!image.has_channel(name + "." + c)) channels.push_back(name + "." + c);
  Image out(image.width(), image.height(), channels);
  const int old_count = image.channel_count();
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x)
      for (int c = 0; c < old_count; ++c) out.at(x, y, c) = image.at(x, y, c);
  const auto ch = *out.rgb_indices(name + ".");
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      const RGB v = values[size_t(y) * size_t(image.width()) + size_t(x)];
      out.at(x, y, ch[0]) = v.r, out.at(x, y, ch[1]) = v.g, out.at(x, y, ch[2]) = v.b;
    }
  return out;
}

}  // namespace caligo
