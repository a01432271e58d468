// Depth of the low-resolution passes and the way back to full resolution (Glatzel 2014,
// "Upscale pass"): nearest-depth upsampling. Each full-resolution pixel looks at the four
// low-resolution taps of its bilinear footprint; where all their depths agree with its own
// (relative difference below the threshold) it takes the bilinear blend, which hides the
// low-resolution blocks; where they do not, it sits on a depth edge and takes the tap of
// nearest depth, so light from behind an edge never leaks onto the surface in front.
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
  float max_diff = 0.0f, best_diff = kInfinity;
  int best = 0;
  for (int i = 0; i < 4; ++i) {
    const float diff = std::abs(rows.d[ys[i]][xs[i]] - d);
    max_diff = std::max(max_diff, diff);
    if (diff < best_diff) {
      best_diff = diff;
      best = i;
    }
  }
  if (max_diff < threshold * d) {
    float r = 0.0f, g = 0.0f, b = 0.0f;
    for (int i = 0; i < 4; ++i) {
      r += w[i] * rows.r[ys[i]][xs[i]];
      g += w[i] * rows.g[ys[i]][xs[i]];
      b += w[i] * rows.b[ys[i]][xs[i]];
    }
    *o_r = r;
    *o_g = g;
    *o_b = b;
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

// 8 consecutive full-resolution pixels; the same decisions as upsample_pixel, lane-wise.
void upsample_lanes(const Rows& rows, int low_width, const int32_t* x0, const int32_t* x1, const float* fx_p,
                    float fy, const float* depth, float threshold, float* o_r, float* o_g, float* o_b) {
  const IBatch i0 = IBatch::load_unaligned(x0), i1 = IBatch::load_unaligned(x1);
  TapFetch fetch{false, x0[0], i0 - x0[0], i1 - x0[0], i0, i1};
  fetch.permute = x1[kLanes - 1] - x0[0] < kLanes && x0[0] + kLanes <= low_width;
  const Batch fx = Batch::load_unaligned(fx_p);
  const Batch d = Batch::load_unaligned(depth);
  const Batch w[4] = {(1.0f - fx) * (1.0f - fy), fx * (1.0f - fy), (1.0f - fx) * fy, fx * fy};
  const int ys[4] = {0, 0, 1, 1}, xs[4] = {0, 1, 0, 1};
  Batch max_diff(0.0f), best_diff(kInfinity);
  Batch best_r(0.0f), best_g(0.0f), best_b(0.0f), r(0.0f), g(0.0f), b(0.0f);
  for (int i = 0; i < 4; ++i) {
    const Batch diff = xsimd::abs(fetch(rows.d[ys[i]], xs[i]) - d);
    const Batch tr = fetch(rows.r[ys[i]], xs[i]);
    const Batch tg = fetch(rows.g[ys[i]], xs[i]);
    const Batch tb = fetch(rows.b[ys[i]], xs[i]);
    max_diff = xsimd::max(max_diff, diff);
    const auto closer = diff < best_diff;  // strict: ties keep the earlier tap, as in the scalar loop
    best_diff = xsimd::select(closer, diff, best_diff);
    best_r = xsimd::select(closer, tr, best_r);
    best_g = xsimd::select(closer, tg, best_g);
    best_b = xsimd::select(closer, tb, best_b);
    r += w[i] * tr;
    g += w[i] * tg;
    b += w[i] * tb;
  }
  const auto smooth = max_diff < threshold * d;
  xsimd::select(smooth, r, best_r).store_unaligned(o_r);
  xsimd::select(smooth, g, best_g).store_unaligned(o_g);
  xsimd::select(smooth, b, best_b).store_unaligned(o_b);
}

}  // namespace

Plane downsample_depth(const Plane& full_depth, int scale) {
  // ceil, as the pipeline sizes its low-resolution view: no full-resolution pixel is left
  // without low-resolution pixels over it.
  const int w = std::max(1, (full_depth.width + scale - 1) / scale);
  const int h = std::max(1, (full_depth.height + scale - 1) / scale);
  Plane low(w, h);
  // The full-resolution pixel under the low-resolution pixel's centre. Both views cover the
  // same film, so that centre is at (x + 0.5) * full / low (= (x + 0.5) scale when the size
  // divides): exact for odd scales, half a full-resolution pixel off for even ones.
  const float rx = float(full_depth.width) / float(w), ry = float(full_depth.height) / float(h);
  for (int y = 0; y < h; ++y) {
    const int fy = std::min(full_depth.height - 1, int((float(y) + 0.5f) * ry));
    for (int x = 0; x < w; ++x) {
      const int fx = std::min(full_depth.width - 1, int((float(x) + 0.5f) * rx));
      low.at(x, y) = full_depth.at(fx, fy);
    }
  }
  return low;
}

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
