// lights/light_profile.cpp's gobo_filter (rotation, offset, wrapped bilinear lookup of
// GoboImage) for 8 texture coordinates at once (xsimd, AVX2 gathers). The same arithmetic in
// the same order as the scalar functions; a caller compiled with FMA contraction rounds
// differently in the last bits, and the lookup is continuous, so results differ by ~1e-6.
// Kept apart from lights/ so that only SIMD code includes xsimd.
#pragma once

#include <immintrin.h>

#include <cmath>

#include <xsimd/xsimd.hpp>

#include "lights/gobo.h"
#include "lights/light.h"

namespace caligo {

class GoboBatch {
 public:
  using B = xsimd::batch<float>;
  using I = xsimd::batch<int32_t>;

  // `gobo.image` must be set. Rotation and offset are the gobo's at the frame's time.
  explicit GoboBatch(const Gobo& gobo)
      : image_(*gobo.image), c_(std::cos(gobo.rotation)), s_(std::sin(gobo.rotation)), offset_(gobo.offset) {}

  // gobo_filter(gobo, (u, v)) per lane.
  void filter(const B& u, const B& v, B& r, B& g, B& b) const {
    // Rotate about the image centre, then shift (gobo_filter).
    const B x = u - B(0.5f), y = v - B(0.5f);
    const B su = B(c_) * x - B(s_) * y + B(0.5f + offset_.x);
    const B sv = B(s_) * x + B(c_) * y + B(0.5f + offset_.y);
    // GoboImage::lookup: pixel centres at (i + 0.5) / n, v flipped, coordinates wrap.
    const float w = float(image_.width()), h = float(image_.height());
    B px = su * B(w) - B(0.5f);
    B py = (B(1.0f) - sv) * B(h) - B(0.5f);
    // x - x is 0 exactly for finite x and NaN otherwise; non-finite lanes are black.
    const auto finite = ((px - px) == B(0.0f)) & ((py - py) == B(0.0f));
    px = xsimd::select(finite, px, B(0.0f));
    py = xsimd::select(finite, py, B(0.0f));
    const B fx = xsimd::floor(px), fy = xsimd::floor(py);
    const B tx = px - fx, ty = py - fy;
    const I x0 = wrap(fx, w), y0 = wrap(fy, h);
    const I x1 = xsimd::select(x0 == I(image_.width() - 1), I(0), x0 + I(1));
    const I y1 = xsimd::select(y0 == I(image_.height() - 1), I(0), y0 + I(1));
    // Float offsets of the four texels' red channel (RGB is three packed floats).
    const I row0 = y0 * I(image_.width()), row1 = y1 * I(image_.width());
    const I i00 = (row0 + x0) * I(3), i10 = (row0 + x1) * I(3), i01 = (row1 + x0) * I(3),
            i11 = (row1 + x1) * I(3);
    const float* data = &image_.data()->r;
    const B one_tx = B(1.0f) - tx, one_ty = B(1.0f) - ty;
    const auto channel = [&](int k) {
      const B top = gather(data + k, i00) * one_tx + gather(data + k, i10) * tx;
      const B bottom = gather(data + k, i01) * one_tx + gather(data + k, i11) * tx;
      return xsimd::select(finite, top * one_ty + bottom * ty, B(0.0f));
    };
    r = channel(0), g = channel(1), b = channel(2);
  }

 private:
  // The wrapped integer texel of an integral float coordinate: f mod n in [0, n).
  // Exact for |f| < 2^24 (the products and differences are integers below that).
  static I wrap(const B& f, float n) {
    B m = f - xsimd::floor(f / B(n)) * B(n);
    m = xsimd::select(m >= B(n), m - B(n), m);
    m = xsimd::select(m < B(0.0f), m + B(n), m);
    return xsimd::to_int(m);
  }
  static B gather(const float* base, const I& index) { return B(_mm256_i32gather_ps(base, index, 4)); }

  const GoboImage& image_;
  float c_, s_;
  Vec2 offset_;
};

}  // namespace caligo
