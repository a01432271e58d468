// The part of the image a render computes, as fractions of the image (pbrt's "cropwindow"):
// x from the left edge, y from the top edge, both in [0, 1]. The full image is
// [0, 1] x [0, 1]. Pixels are chosen as pbrt does: pixel columns ceil(W x0) .. ceil(W x1) - 1,
// so two crops that share an edge share no pixel and together cover what their union covers.
#pragma once

#include <cmath>
#include <string>

#include "core/vec.h"

namespace caligo {

// Pixels [min.x, max.x) x [min.y, max.y).
struct PixelBounds {
  Vec2i min, max;
  bool empty() const { return max.x <= min.x || max.y <= min.y; }
  int width() const { return max.x - min.x; }
  int height() const { return max.y - min.y; }
};

struct CropWindow {
  float x0 = 0.0f, x1 = 1.0f, y0 = 0.0f, y1 = 1.0f;

  bool full() const { return x0 == 0.0f && x1 == 1.0f && y0 == 0.0f && y1 == 1.0f; }
  PixelBounds pixels(Vec2i resolution) const {
    auto edge = [](int n, float f) { return int(std::ceil(double(n) * double(f))); };
    return {{edge(resolution.x, x0), edge(resolution.y, y0)}, {edge(resolution.x, x1), edge(resolution.y, y1)}};
  }
};

// Why a crop window is invalid ("" when it is valid): each bound finite and in [0, 1],
// x0 < x1 and y0 < y1. Whether it holds a pixel depends on the resolution: see pixels().
inline std::string crop_window_problem(const CropWindow& c) {
  auto in_unit = [](float v) { return std::isfinite(v) && v >= 0.0f && v <= 1.0f; };
  if (!in_unit(c.x0) || !in_unit(c.x1) || !in_unit(c.y0) || !in_unit(c.y1))
    return "expected every bound in [0, 1]";
  if (!(c.x0 < c.x1)) return "expected x0 < x1";
  if (!(c.y0 < c.y1)) return "expected y0 < y1";
  return "";
}

}  // namespace caligo
