// The images the real-time passes read and write: planar float buffers (one plane per
// channel), row-major, origin top-left. Planar, unlike image/Image's interleaved pixels,
// because every pass runs SIMD over runs of x and loads 8 neighbouring pixels of one
// channel with one instruction.
#pragma once

#include <cassert>
#include <cstddef>
#include <vector>

#include "core/rgb.h"

namespace caligo {

struct Plane {
  int width = 0, height = 0;
  std::vector<float> data;

  Plane() = default;
  Plane(int w, int h, float fill = 0.0f) : width(w), height(h), data(size_t(w) * size_t(h), fill) {}

  float& at(int x, int y) {
    assert(x >= 0 && x < width && y >= 0 && y < height);
    return data[size_t(y) * size_t(width) + size_t(x)];
  }
  float at(int x, int y) const {
    assert(x >= 0 && x < width && y >= 0 && y < height);
    return data[size_t(y) * size_t(width) + size_t(x)];
  }
  float* row(int y) { return data.data() + size_t(y) * size_t(width); }
  const float* row(int y) const { return data.data() + size_t(y) * size_t(width); }
  void fill(float v) { std::fill(data.begin(), data.end(), v); }
};

struct ColorPlanes {
  Plane r, g, b;

  ColorPlanes() = default;
  ColorPlanes(int w, int h) : r(w, h), g(w, h), b(w, h) {}
  int width() const { return r.width; }
  int height() const { return r.height; }
  RGB at(int x, int y) const { return {r.at(x, y), g.at(x, y), b.at(x, y)}; }
  void set(int x, int y, RGB c) {
    r.at(x, y) = c.r;
    g.at(x, y) = c.g;
    b.at(x, y) = c.b;
  }
  void add(int x, int y, RGB c) {
    r.at(x, y) += c.r;
    g.at(x, y) += c.g;
    b.at(x, y) += c.b;
  }
  void clear() {
    r.fill(0.0f);
    g.fill(0.0f);
    b.fill(0.0f);
  }
  // this += weight * other, per channel; same size required.
  void add(const ColorPlanes& other, RGB weight = RGB(1.0f)) {
    Plane* const out[3] = {&r, &g, &b};
    const Plane* const in[3] = {&other.r, &other.g, &other.b};
    for (int c = 0; c < 3; ++c)
      for (size_t i = 0; i < out[c]->data.size(); ++i) out[c]->data[i] += weight[c] * in[c]->data[i];
  }
};

}  // namespace caligo
