// Gather pass (Glatzel 2014): a separable bilateral Gaussian over the accumulation buffer
// that blurs the interleaved-sampling pattern away without bleeding light across depth
// edges. Tap k of 2r + 1 weighs exp(-k^2 / (2 sigma^2)) with sigma = r / 2.55, which for
// r = 7 reproduces the shape of the seed's 15 weights (0.1445, 0.1354, ..., 0.0055) to within 3 %, times
// the depth weight exp(-falloff |d - d0 - k s| / d0); the sum is normalised by the weights,
// and taps outside the image are dropped (the weights renormalise).
//
// s is the depth's slope along the line at the centre: the smaller of its two one-sided
// differences where they agree in sign, else 0 (minmod). On a surface facing the camera s = 0
// and the weight is the seed's. On a wall seen edge-on the depth changes by s per pixel
// (several per cent of d at grazing angles), which the seed's weight, on relative depth
// alone, rejects tap by tap: the gather then blurs nothing across the wall, and the
// interleaving pattern stays as vertical streaks. Predicted along the plane, the taps on the
// wall agree again; across a depth edge the smaller one-sided difference is the near side's,
// so taps beyond the edge still miss the prediction by the jump and are rejected.
// The one-sided slope is not the central one on curved depth (a floor's rows, 1/y), so the
// taps of one side fit better than the other's and the blur leans: opt-in
// (RealtimeSettings::gather_follow_slope), the seed's weight by default.
#include <xsimd/xsimd.hpp>

#include <cmath>
#include <vector>

#include "core/parallel.h"
#include "realtime/passes.h"

namespace caligo {
namespace {

using Batch = xsimd::batch<float>;
constexpr int kLanes = int(Batch::size);

std::vector<float> gaussian_weights(int radius) {
  std::vector<float> w(size_t(radius) + 1);
  const float sigma = std::max(radius, 1) / 2.55f;
  for (int k = 0; k <= radius; ++k) w[size_t(k)] = std::exp(-float(k * k) / (2.0f * sigma * sigma));
  return w;
}

// One output pixel of a 1D pass: taps at base + k * stride for k in [-lo, hi].
struct Line {
  const float* r;
  const float* g;
  const float* b;
  const float* d;
};

float minmod(float a, float b) { return a * b > 0.0f ? (std::abs(a) < std::abs(b) ? a : b) : 0.0f; }

void gather_scalar_pixel(const Line& in, int i, int stride, int lo, int hi, const std::vector<float>& w,
                         float falloff, bool follow_slope, float* out_r, float* out_g, float* out_b) {
  const float d0 = in.d[i * stride];
  const float scale = falloff / d0;
  const float slope = follow_slope && lo > 0 && hi > 0
                          ? minmod(d0 - in.d[(i - 1) * stride], in.d[(i + 1) * stride] - d0)
                          : 0.0f;
  float sr = 0.0f, sg = 0.0f, sb = 0.0f, sw = 0.0f;
  for (int k = -lo; k <= hi; ++k) {
    const int j = (i + k) * stride;
    const float wk = w[size_t(std::abs(k))] * std::exp(-std::abs(in.d[j] - d0 - float(k) * slope) * scale);
    sr += wk * in.r[j];
    sg += wk * in.g[j];
    sb += wk * in.b[j];
    sw += wk;
  }
  // sw >= w[0] > 0: the centre tap always has depth weight 1.
  *out_r = sr / sw;
  *out_g = sg / sw;
  *out_b = sb / sw;
}

// 8 output pixels at once, from taps p + k * step (step in floats): contiguous lanes.
void gather_simd_lanes(const float* r, const float* g, const float* b, const float* d, ptrdiff_t step, int lo,
                       int hi, const std::vector<float>& w, float falloff, bool follow_slope, float* out_r,
                       float* out_g, float* out_b) {
  const Batch d0 = Batch::load_unaligned(d);
  const Batch scale = falloff / d0;
  Batch slope(0.0f);
  if (follow_slope && lo > 0 && hi > 0) {
    const Batch back = d0 - Batch::load_unaligned(d - step), ahead = Batch::load_unaligned(d + step) - d0;
    const Batch smaller = xsimd::select(xsimd::abs(back) < xsimd::abs(ahead), back, ahead);
    slope = xsimd::select(back * ahead > 0.0f, smaller, Batch(0.0f));
  }
  Batch sr(0.0f), sg(0.0f), sb(0.0f), sw(0.0f);
  for (int k = -lo; k <= hi; ++k) {
    const ptrdiff_t j = k * step;
    const Batch predicted = d0 + float(k) * slope;
    const Batch wk =
        w[size_t(std::abs(k))] * xsimd::exp(-xsimd::abs(Batch::load_unaligned(d + j) - predicted) * scale);
    sr += wk * Batch::load_unaligned(r + j);
    sg += wk * Batch::load_unaligned(g + j);
    sb += wk * Batch::load_unaligned(b + j);
    sw += wk;
  }
  (sr / sw).store_unaligned(out_r);
  (sg / sw).store_unaligned(out_g);
  (sb / sw).store_unaligned(out_b);
}

void horizontal(const ColorPlanes& in, const Plane& depth, int radius, float falloff, bool follow_slope, bool simd,
                const std::vector<float>& w, ColorPlanes& out) {
  const int width = in.width();
  parallel_for(in.height(), [&](int y) {
    const Line line{in.r.row(y), in.g.row(y), in.b.row(y), depth.row(y)};
    float* o_r = out.r.row(y);
    float* o_g = out.g.row(y);
    float* o_b = out.b.row(y);
    int x = 0;
    while (x < width) {
      // Lanes whose taps all lie inside the row go 8 at a time.
      if (simd && x >= radius && x + kLanes - 1 + radius < width) {
        gather_simd_lanes(line.r + x, line.g + x, line.b + x, line.d + x, 1, radius, radius, w, falloff,
                          follow_slope, o_r + x, o_g + x, o_b + x);
        x += kLanes;
        continue;
      }
      gather_scalar_pixel(line, x, 1, std::min(radius, x), std::min(radius, width - 1 - x), w, falloff,
                          follow_slope, o_r + x, o_g + x, o_b + x);
      ++x;
    }
  });
}

void vertical(const ColorPlanes& in, const Plane& depth, int radius, float falloff, bool follow_slope, bool simd,
              const std::vector<float>& w, ColorPlanes& out) {
  const int width = in.width(), height = in.height();
  parallel_for(height, [&](int y) {
    const int lo = std::min(radius, y), hi = std::min(radius, height - 1 - y);
    float* o_r = out.r.row(y);
    float* o_g = out.g.row(y);
    float* o_b = out.b.row(y);
    int x = 0;
    if (simd) {
      for (; x + kLanes <= width; x += kLanes)
        gather_simd_lanes(in.r.row(y) + x, in.g.row(y) + x, in.b.row(y) + x, depth.row(y) + x, width, lo, hi,
                          w, falloff, follow_slope, o_r + x, o_g + x, o_b + x);
    }
    for (; x < width; ++x) {
      // Column x seen as a line with stride `width`, centred on row y.
      const Line column{in.r.data.data() + x, in.g.data.data() + x, in.b.data.data() + x,
                        depth.data.data() + x};
      gather_scalar_pixel(column, y, width, lo, hi, w, falloff, follow_slope, o_r + x, o_g + x, o_b + x);
    }
  });
}

}  // namespace

ColorPlanes bilateral_gather(const ColorPlanes& in, const Plane& depth, int radius, float depth_falloff,
                             bool simd, bool follow_slope) {
  if (radius <= 0) return in;
  const std::vector<float> w = gaussian_weights(radius);
  ColorPlanes tmp(in.width(), in.height()), out(in.width(), in.height());
  horizontal(in, depth, radius, depth_falloff, follow_slope, simd, w, tmp);
  vertical(tmp, depth, radius, depth_falloff, follow_slope, simd, w, out);
  return out;
}

}  // namespace caligo
