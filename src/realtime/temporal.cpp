// Temporal reprojection (Glatzel 2014, after DICE's SSAO in Battlefield 3): each pixel
// finds where its surface point was in the previous frame and blends with the history
// there: out = lerp(history, current, alpha).
//
// History validity is decided per bilinear tap: a tap whose stored depth differs from the
// reprojected depth by more than kDepthTolerance (relative) belongs to another surface
// (disocclusion) and gets weight 0; the remaining taps are renormalised, and with none
// left the pixel takes the current frame. Sky pixels (depth kSkyDepth) reproject by
// direction alone and accept only sky history.
//
// Luminance weight: alpha = blend + (1 - blend) c^2 with c = |L_cur - L_hist| /
// max(L_cur, L_hist): a light switching on or a shaft sweeping through (c near 1) replaces
// the history at once, while zero-mean noise (c small, and symmetric in sign) barely
// changes alpha and so does not bias the converged mean.
#include <xsimd/xsimd.hpp>

#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include "realtime/passes.h"
#include "realtime/scene_buffers.h"

namespace caligo {
namespace {

constexpr float kDepthTolerance = 0.02f;
constexpr float kSkyThreshold = 0.5f * kSkyDepth;

float luminance(float r, float g, float b) { return 0.2126f * r + 0.7152f * g + 0.0722f * b; }

// History colour at film position q with expected depth `expect` (sky: < 0); false if
// every tap is rejected.
bool sample_history(const ColorPlanes& history, const Plane& history_depth, Vec2 q, float expect, RGB& out) {
  const float u = q.x - 0.5f, v = q.y - 0.5f;
  const int x0 = int(std::floor(u)), y0 = int(std::floor(v));
  const float fx = u - float(x0), fy = v - float(y0);
  const int w = history.width(), h = history.height();
  float sum_w = 0.0f;
  RGB sum;
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 2; ++i) {
      const int x = std::clamp(x0 + i, 0, w - 1), y = std::clamp(y0 + j, 0, h - 1);
      const float hd = history_depth.at(x, y);
      const bool match = expect < 0.0f
                             ? hd >= kSkyThreshold
                             : hd < kSkyThreshold && std::abs(hd - expect) <= kDepthTolerance * expect;
      if (!match) continue;
      const float wt = (i ? fx : 1.0f - fx) * (j ? fy : 1.0f - fy);
      sum += history.at(x, y) * wt;
      sum_w += wt;
    }
  }
  if (!(sum_w > 1e-6f)) return false;
  out = sum / sum_w;
  return true;
}

// Where pixel (x, y) of `view` was in `history_view`: film position and expected depth
// (-1 for the sky); false when it was outside the previous image.
bool reproject(const View& view, const View& history_view, int x, int y, float depth, Vec2& q,
               float& expect) {
  const Vec2 film{float(x) + 0.5f, float(y) + 0.5f};
  Vec3 p;
  if (depth >= kSkyThreshold) {
    // Infinitely far: only the direction matters (a point one metre out from the old eye).
    p = history_view.project(history_view.eye + view.ray(film).direction);
    expect = -1.0f;
  } else {
    p = history_view.project(view.unproject(film, depth));
    expect = p.z;
  }
  if (!(p.z > 0.0f)) return false;
  q = {p.x, p.y};
  return q.x >= 0.0f && q.y >= 0.0f && q.x < float(history_view.resolution.x) &&
         q.y < float(history_view.resolution.y);
}

RGB blend_pixel(RGB current, RGB hist, float blend) {
  const float lc = luminance(current.r, current.g, current.b), lh = luminance(hist.r, hist.g, hist.b);
  const float top = std::max(lc, lh);
  const float c = top > 0.0f ? std::abs(lc - lh) / top : 0.0f;
  const float alpha = blend + (1.0f - blend) * c * c;
  return hist + (current - hist) * alpha;
}

using Batch = xsimd::batch<float>;
using IBatch = xsimd::batch<int32_t>;
using Mask = xsimd::batch_bool<float>;
constexpr int kLanes = int(Batch::size);

// The SIMD row for two perspective views: the same decisions as the scalar pixel, with
// unproject + project folded into one affine map per row (a perspective view's ray through
// film x is forward + right a(x) + up b(y), whose forward component is 1, so the point at
// linear depth d is eye + d (forward + right a + up b)).
struct PerspectiveReprojection {
  const View& view;
  const View& hist;
  Vec3 eye_delta;  // view.eye - hist.eye
  float sx, sy;    // a(x) = sx (2 (x + 0.5) / W - 1), b(y) likewise with sy
  float hsx, hsy;  // 1 / (tan * aspect), 1 / tan of the history view

  PerspectiveReprojection(const View& v, const View& h)
      : view(v),
        hist(h),
        eye_delta(v.eye - h.eye),
        sx(v.tan_half_fov_y * v.aspect),
        sy(v.tan_half_fov_y),
        hsx(1.0f / (h.tan_half_fov_y * h.aspect)),
        hsy(1.0f / h.tan_half_fov_y) {}

  void row(const ColorPlanes& current, const Plane& depth, const ColorPlanes& history,
           const Plane& history_depth, float blend, int y, int x_begin, int x_end, ColorPlanes& out) const;
};

Batch hdot(Vec3 a, const Batch& x, const Batch& y, const Batch& z) { return a.x * x + a.y * y + a.z * z; }

// Where 8 pixels of the current frame were in the history's view: its pixel coordinates, the
// depth expected there (z along the old view axis) and which lanes land inside it.
struct Reprojected {
  Batch qx, qy, expect;
  Mask sky, valid;
};

// The history's colour at the reprojected lanes: bilinear over the taps whose depth matches
// (sky with sky, surfaces within kDepthTolerance); `valid` drops lanes with no matching tap.
struct HistoryColour {
  Batch r, g, b;
  Mask valid;
};

HistoryColour sample_history(const Reprojected& q, const ColorPlanes& history, const Plane& history_depth, int hw,
                             int hh) {
  const Batch u = q.qx - 0.5f, v = q.qy - 0.5f;
  const Batch fu = xsimd::floor(u), fv = xsimd::floor(v);
  const Batch fx = u - fu, fy = v - fv;
  // Invalid lanes may hold garbage coordinates; clamping keeps their gathers in bounds.
  const Batch cu = xsimd::min(xsimd::max(fu, Batch(-1.0f)), Batch(float(hw)));
  const Batch cv = xsimd::min(xsimd::max(fv, Batch(-1.0f)), Batch(float(hh)));
  const IBatch iu = xsimd::batch_cast<int32_t>(xsimd::select(q.valid, cu, Batch(0.0f)));
  const IBatch iv = xsimd::batch_cast<int32_t>(xsimd::select(q.valid, cv, Batch(0.0f)));
  const IBatch zero(0), xmax(hw - 1), ymax(hh - 1);
  const IBatch xs[2] = {xsimd::min(xsimd::max(iu, zero), xmax), xsimd::min(xsimd::max(iu + 1, zero), xmax)};
  const IBatch ys[2] = {xsimd::min(xsimd::max(iv, zero), ymax) * hw, xsimd::min(xsimd::max(iv + 1, zero), ymax) * hw};
  Batch sw(0.0f), sr(0.0f), sg(0.0f), sb(0.0f);
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 2; ++i) {
      const IBatch idx = ys[j] + xs[i];
      const Batch hd = Batch::gather(history_depth.data.data(), idx);
      const Mask match = (q.sky & (hd >= kSkyThreshold)) |
                         (~q.sky & (hd < kSkyThreshold) & (xsimd::abs(hd - q.expect) <= kDepthTolerance * q.expect));
      const Batch wt = xsimd::select(match, (i ? fx : 1.0f - fx) * (j ? fy : 1.0f - fy), Batch(0.0f));
      sr += wt * Batch::gather(history.r.data.data(), idx);
      sg += wt * Batch::gather(history.g.data.data(), idx);
      sb += wt * Batch::gather(history.b.data.data(), idx);
      sw += wt;
    }
  }
  const Mask valid = q.valid & (sw > 1e-6f);
  const Batch inv_w = 1.0f / xsimd::select(valid, sw, Batch(1.0f));
  return {sr * inv_w, sg * inv_w, sb * inv_w, valid};
}

void PerspectiveReprojection::row(const ColorPlanes& current, const Plane& depth, const ColorPlanes& history,
                                  const Plane& history_depth, float blend, int y, int x_begin, int x_end,
                                  ColorPlanes& out) const {
  alignas(32) static constexpr float kLane[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  const int W = view.resolution.x, H = view.resolution.y;
  const int hw = hist.resolution.x, hh = hist.resolution.y;
  const float by = (1.0f - 2.0f * (float(y) + 0.5f) / float(H)) * sy;
  const Vec3 base = view.forward + view.up * by;
  for (int x = x_begin; x + kLanes <= x_end; x += kLanes) {
    const Batch px = Batch::load_aligned(kLane) + float(x);
    const Batch ax = ((px + 0.5f) * (2.0f / float(W)) - 1.0f) * sx;
    const Batch dx = base.x + view.right.x * ax, dy = base.y + view.right.y * ax,
                dz = base.z + view.right.z * ax;
    const Batch d = Batch::load_unaligned(depth.row(y) + x);
    Reprojected q;
    q.sky = d >= kSkyThreshold;
    const Batch dd = xsimd::select(q.sky, Batch(0.0f), d);
    // Sky: the direction alone, seen from the old eye.
    const Batch ex = xsimd::select(q.sky, Batch(0.0f), Batch(eye_delta.x));
    const Batch ey = xsimd::select(q.sky, Batch(0.0f), Batch(eye_delta.y));
    const Batch ez = xsimd::select(q.sky, Batch(0.0f), Batch(eye_delta.z));
    const Batch m = xsimd::select(q.sky, Batch(1.0f), dd);
    const Batch rx = ex + m * dx, ry = ey + m * dy, rz = ez + m * dz;
    q.expect = hdot(hist.forward, rx, ry, rz);
    const Batch inv_z = 1.0f / q.expect;
    q.qx = (hdot(hist.right, rx, ry, rz) * inv_z * hsx + 1.0f) * (0.5f * float(hw));
    q.qy = (1.0f - hdot(hist.up, rx, ry, rz) * inv_z * hsy) * (0.5f * float(hh));
    q.valid = (q.expect > 0.0f) & (q.qx >= 0.0f) & (q.qy >= 0.0f) & (q.qx < float(hw)) & (q.qy < float(hh));
    const HistoryColour h = sample_history(q, history, history_depth, hw, hh);
    const Batch cr = Batch::load_unaligned(current.r.row(y) + x);
    const Batch cg = Batch::load_unaligned(current.g.row(y) + x);
    const Batch cb = Batch::load_unaligned(current.b.row(y) + x);
    const Batch lc = 0.2126f * cr + 0.7152f * cg + 0.0722f * cb;
    const Batch lh = 0.2126f * h.r + 0.7152f * h.g + 0.0722f * h.b;
    const Batch top = xsimd::max(lc, lh);
    const Batch c = xsimd::select(
        top > 0.0f, xsimd::abs(lc - lh) / xsimd::select(top > 0.0f, top, Batch(1.0f)), Batch(0.0f));
    const Batch alpha = xsimd::select(h.valid, blend + (1.0f - blend) * c * c, Batch(1.0f));
    (xsimd::select(h.valid, h.r + (cr - h.r) * alpha, cr)).store_unaligned(out.r.row(y) + x);
    (xsimd::select(h.valid, h.g + (cg - h.g) * alpha, cg)).store_unaligned(out.g.row(y) + x);
    (xsimd::select(h.valid, h.b + (cb - h.b) * alpha, cb)).store_unaligned(out.b.row(y) + x);
  }
}

}  // namespace

ColorPlanes temporal_reproject(const ColorPlanes& current, const Plane& depth, const View& view,
                               const ColorPlanes& history, const Plane& history_depth,
                               const View& history_view, float blend, bool simd) {
  ColorPlanes out;
  temporal_reproject(current, depth, view, history, history_depth, history_view, blend, out, simd);
  return out;
}

void temporal_reproject(const ColorPlanes& current, const Plane& depth, const View& view,
                        const ColorPlanes& history, const Plane& history_depth, const View& history_view,
                        float blend, ColorPlanes& out, bool simd) {
  if (out.width() != current.width() || out.height() != current.height())
    out = ColorPlanes(current.width(), current.height());
  const bool fast = simd && history.width() > 0 && view.projection == Projection::perspective &&
                    history_view.projection == Projection::perspective;
  const PerspectiveReprojection lanes(view, history_view);
  parallel_for(current.height(), [&](int y) {
    int x = 0;
    if (fast) {
      const int end = current.width() / kLanes * kLanes;
      lanes.row(current, depth, history, history_depth, blend, y, 0, end, out);
      x = end;
    }
    for (; x < current.width(); ++x) {
      const RGB cur = current.at(x, y);
      Vec2 q;
      float expect;
      RGB hist;
      const bool valid = history.width() > 0 &&
                         reproject(view, history_view, x, y, depth.at(x, y), q, expect) &&
                         sample_history(history, history_depth, q, expect, hist);
      out.set(x, y, valid ? blend_pixel(cur, hist, blend) : cur);
    }
  });
}

}  // namespace caligo
