// The way back to full resolution (Glatzel 2014, "Upscale pass"): depth-aware upsampling.
// Each full-resolution pixel looks at the four low-resolution taps of its bilinear footprint
// and blends, with their bilinear weights, those whose depth agrees with its own (relative
// difference below the threshold): where all four agree this is the bilinear blend, which
// hides the low-resolution blocks; along a depth edge it interpolates along the edge between
// the taps of the pixel's own surface, so the edge has no stair-steps of a block's size. Where
// no tap agrees it takes the tap of nearest depth (the seed's rule), so light from behind an
// edge never leaks onto the surface in front.
#include <immintrin.h>
#include <xsimd/xsimd.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/parallel.h"
#include "realtime/passes.h"

namespace caligo {
namespace {

using Batch = xsimd::batch<float>;
using IBatch = xsimd::batch<int32_t>;
constexpr int kLanes = int(Batch::size);

// Bilinear footprint along one axis of each full-resolution pixel centre.
struct Footprint {
  std::vector<int32_t> i0, i1;
  std::vector<float> f;  // weight of i1
};

Footprint footprint(int full, int low) {
  Footprint fp;
  fp.i0.resize(size_t(full));
  fp.i1.resize(size_t(full));
  fp.f.resize(size_t(full));
  const float ratio = float(low) / float(full);
  for (int i = 0; i < full; ++i) {
    const float u = (float(i) + 0.5f) * ratio - 0.5f;
    const float fl = std::floor(u);
    const int a = int(fl);
    fp.i0[size_t(i)] = std::clamp(a, 0, low - 1);
    fp.i1[size_t(i)] = std::clamp(a + 1, 0, low - 1);
    fp.f[size_t(i)] = u - fl;
  }
  return fp;
}

struct Rows {
  const float* r[2];
  const float* g[2];
  const float* b[2];
  const float* d[2];
};

void upsample_pixel(const Rows& rows, int x0, int x1, float fx, float fy, float d, float threshold,
                    float* o_r, float* o_g, float* o_b) {
  const int xs[4] = {x0, x1, x0, x1}, ys[4] = {0, 0, 1, 1};
  const float w[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
  float best_diff = kInfinity, weight = 0.0f, r = 0.0f, g = 0.0f, b = 0.0f;
  int best = 0;
  for (int i = 0; i < 4; ++i) {
    const float diff = std::abs(rows.d[ys[i]][xs[i]] - d);
    if (diff < best_diff) {
      best_diff = diff;
      best = i;
    }
    if (diff < threshold * d) {
      weight += w[i];
      r += w[i] * rows.r[ys[i]][xs[i]];
      g += w[i] * rows.g[ys[i]][xs[i]];
      b += w[i] * rows.b[ys[i]][xs[i]];
    }
  }
  if (weight > 0.0f) {
    *o_r = r / weight;
    *o_g = g / weight;
    *o_b = b / weight;
    return;
  }
  *o_r = rows.r[ys[best]][xs[best]];
  *o_g = rows.g[ys[best]][xs[best]];
  *o_b = rows.b[ys[best]][xs[best]];
}

// The taps of 8 lanes from one row: when the lanes' columns lie within 8 of the first
// (any scale >= 2), one unaligned load and an in-register permute (AVX2 vpermps) replace
// the gather.
struct TapFetch {
  bool permute;
  int32_t base;
  IBatch rel0, rel1;  // column - base, for the permute
  IBatch i0, i1;      // columns, for the gather

  Batch operator()(const float* row, int which) const {
    if (permute) {
      const __m256 v = Batch::load_unaligned(row + base);
      return Batch(_mm256_permutevar8x32_ps(v, which ? rel1 : rel0));
    }
    return Batch::gather(row, which ? i1 : i0);
  }
};

// 8 consecutive full-resolution pixels; the same blend as upsample_pixel, lane-wise.
void upsample_lanes(const Rows& rows, int low_width, const int32_t* x0, const int32_t* x1, const float* fx_p,
                    float fy, const float* depth, float threshold, float* o_r, float* o_g, float* o_b) {
  const IBatch i0 = IBatch::load_unaligned(x0), i1 = IBatch::load_unaligned(x1);
  TapFetch fetch{false, x0[0], i0 - x0[0], i1 - x0[0], i0, i1};
  fetch.permute = x1[kLanes - 1] - x0[0] < kLanes && x0[0] + kLanes <= low_width;
  const Batch fx = Batch::load_unaligned(fx_p);
  const Batch d = Batch::load_unaligned(depth);
  const Batch w[4] = {(1.0f - fx) * (1.0f - fy), fx * (1.0f - fy), (1.0f - fx) * fy, fx * fy};
  const int ys[4] = {0, 0, 1, 1}, xs[4] = {0, 1, 0, 1};
  Batch weight(0.0f), best_diff(kInfinity);
  Batch best_r(0.0f), best_g(0.0f), best_b(0.0f), r(0.0f), g(0.0f), b(0.0f);
  const Batch agree = threshold * d;
  for (int i = 0; i < 4; ++i) {
    const Batch diff = xsimd::abs(fetch(rows.d[ys[i]], xs[i]) - d);
    const Batch tr = fetch(rows.r[ys[i]], xs[i]);
    const Batch tg = fetch(rows.g[ys[i]], xs[i]);
    const Batch tb = fetch(rows.b[ys[i]], xs[i]);
    const auto closer = diff < best_diff;  // strict: ties keep the earlier tap, as in the scalar loop
    best_diff = xsimd::select(closer, diff, best_diff);
    best_r = xsimd::select(closer, tr, best_r);
    best_g = xsimd::select(closer, tg, best_g);
    best_b = xsimd::select(closer, tb, best_b);
    const Batch wi = xsimd::select(diff < agree, w[i], Batch(0.0f));
    weight += wi;
    r += wi * tr;
    g += wi * tg;
    b += wi * tb;
  }
  const auto some = weight > 0.0f;
  const Batch safe = xsimd::select(some, weight, Batch(1.0f));
  xsimd::select(some, r / safe, best_r).store_unaligned(o_r);
  xsimd::select(some, g / safe, best_g).store_unaligned(o_g);
  xsimd::select(some, b / safe, best_b).store_unaligned(o_b);
}

}  // namespace

ColorPlanes upsample_nearest_depth(const ColorPlanes& low, const Plane& low_depth, const Plane& full_depth,
                                   float relative_threshold, bool simd) {
  ColorPlanes out;
  upsample_nearest_depth(low, low_depth, full_depth, out, relative_threshold, simd);
  return out;
}

void upsample_nearest_depth(const ColorPlanes& low, const Plane& low_depth, const Plane& full_depth,
                            ColorPlanes& out, float relative_threshold, bool simd) {
  const int fw = full_depth.width, fh = full_depth.height;
  if (out.width() != fw || out.height() != fh) out = ColorPlanes(fw, fh);
  const Footprint fx = footprint(fw, low.width()), fy = footprint(fh, low.height());
  parallel_for(fh, [&](int y) {
    const int y0 = fy.i0[size_t(y)], y1 = fy.i1[size_t(y)];
    const Rows rows{{low.r.row(y0), low.r.row(y1)},
                    {low.g.row(y0), low.g.row(y1)},
                    {low.b.row(y0), low.b.row(y1)},
                    {low_depth.row(y0), low_depth.row(y1)}};
    const float wy = fy.f[size_t(y)];
    const float* d = full_depth.row(y);
    float* o_r = out.r.row(y);
    float* o_g = out.g.row(y);
    float* o_b = out.b.row(y);
    int x = 0;
    if (simd) {
      for (; x + kLanes <= fw; x += kLanes)
        upsample_lanes(rows, low.width(), fx.i0.data() + x, fx.i1.data() + x, fx.f.data() + x, wy, d + x,
                       relative_threshold, o_r + x, o_g + x, o_b + x);
    }
    for (; x < fw; ++x)
      upsample_pixel(rows, fx.i0[size_t(x)], fx.i1[size_t(x)], fx.f[size_t(x)], wy, d[x], relative_threshold,
                     o_r + x, o_g + x, o_b + x);
  });
}

}  // namespace caligo
