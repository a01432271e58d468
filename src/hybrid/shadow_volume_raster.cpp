// The eye pass of the shadow volumes (shadow_volume.h): their triangles rasterised into
// full-width bands of rows, keeping per pixel the nearest and farthest surface in front of
// the opaque depth and the signed crossings.
#include "hybrid/shadow_volume.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include <xsimd/xsimd.hpp>

#include "core/parallel.h"
#include "realtime/raster_row.h"
#include "realtime/scene_buffers.h"

namespace caligo {
namespace {

struct VolumeScene {
  RasterScene scene;
  std::vector<int8_t> sign;  // per rasterised triangle: +1 turned to the eye (entering), -1 away
};

// The farthest opaque depth of each kCell x kCell block of pixels, to drop before set-up
// the triangles that lie behind the opaque surface wherever they could cover a pixel. Most
// of a volume's far cap (tens of thousands of triangles) lies under the ground.
class DepthCull {
 public:
  static constexpr int kCell = 16;

  // keep: the depth bias factor, 1 - ShadowVolumeOptions::depth_bias.
  DepthCull(const View& view, const Plane& depth, float keep)
      : view_(view),
        perspective_(view.projection == Projection::perspective),
        cells_x_((depth.width + kCell - 1) / kCell),
        cells_y_((depth.height + kCell - 1) / kCell),
        farthest_(size_t(cells_x_) * size_t(cells_y_), 0.0f) {
    const float half_w = 0.5f * float(view.resolution.x), half_h = 0.5f * float(view.resolution.y);
    scale_x_ = half_w / (perspective_ ? view.tan_half_fov_y * view.aspect : view.half_width);
    scale_y_ = half_h / (perspective_ ? view.tan_half_fov_y : view.half_height);
    for (int y = 0; y < depth.height; ++y) {
      float* cells = &farthest_[size_t(y / kCell) * size_t(cells_x_)];
      for (int x = 0; x < depth.width; ++x) {
        // A NaN depth never passes the per-pixel test, so it may be ignored; +inf keeps all.
        const float d = depth.at(x, y) * std::max(keep, 1.0f);
        if (d > cells[x / kCell]) cells[x / kCell] = d;
      }
    }
  }

  // True when no pixel centre the triangle can cover has an opaque surface behind it.
  // Conservative: the projected bounds are padded by two pixels, triangles reaching near
  // the eye plane are kept, and the depth comparison has a 1e-4 relative margin (the
  // rasteriser's key is exact to ~1e-6).
  bool hidden(Vec3 p0, Vec3 p1, Vec3 p2) const {
    float lo_x = kInfinity, hi_x = -kInfinity, lo_y = kInfinity, hi_y = -kInfinity, near = kInfinity;
    for (Vec3 p : {p0, p1, p2}) {
      const Vec3 d = p - view_.eye;
      const float z = dot(d, view_.forward);
      if (!(z > (perspective_ ? 1.0e-3f : 0.0f))) return false;  // clipped: let set-up decide
      const float inv = perspective_ ? 1.0f / z : 1.0f;
      const float sx = 0.5f * float(view_.resolution.x) + dot(d, view_.right) * inv * scale_x_;
      const float sy = 0.5f * float(view_.resolution.y) - dot(d, view_.up) * inv * scale_y_;
      lo_x = std::min(lo_x, sx), hi_x = std::max(hi_x, sx);
      lo_y = std::min(lo_y, sy), hi_y = std::max(hi_y, sy);
      near = std::min(near, z);
    }
    if (!(std::isfinite(lo_x) && std::isfinite(hi_x) && std::isfinite(lo_y) && std::isfinite(hi_y)))
      return false;
    const float limit_x = float(view_.resolution.x) + 4.0f, limit_y = float(view_.resolution.y) + 4.0f;
    const int x0 = int(std::clamp(lo_x - 2.0f, 0.0f, limit_x)) / kCell;
    const int x1 = std::min(int(std::clamp(hi_x + 2.0f, 0.0f, limit_x)) / kCell, cells_x_ - 1);
    const int y0 = int(std::clamp(lo_y - 2.0f, 0.0f, limit_y)) / kCell;
    const int y1 = std::min(int(std::clamp(hi_y + 2.0f, 0.0f, limit_y)) / kCell, cells_y_ - 1);
    const float behind = near * (1.0f - 1.0e-4f);
    for (int cy = y0; cy <= y1; ++cy)
      for (int cx = x0; cx <= x1; ++cx)
        if (!(farthest_[size_t(cy) * size_t(cells_x_) + size_t(cx)] < behind)) return false;
    return true;  // also when the padded bounds miss the screen (no cell visited)
  }

 private:
  const View& view_;
  bool perspective_;
  int cells_x_, cells_y_;
  float scale_x_ = 1.0f, scale_y_ = 1.0f;
  std::vector<float> farthest_;
};

VolumeScene gather_triangles(std::span<const ShadowVolume> volumes, const View& view,
                             const ShadowVolumeOptions& options, const DepthCull& cull) {
  VolumeScene out;
  const bool perspective = view.projection == Projection::perspective;
  for (const ShadowVolume& v : volumes) {
    auto add = [&](size_t begin, size_t count) {
      for (size_t t = begin; t < begin + count; ++t) {
        const Vec3 p0 = v.mesh.positions[v.mesh.indices[3 * t]],
                   p1 = v.mesh.positions[v.mesh.indices[3 * t + 1]],
                   p2 = v.mesh.positions[v.mesh.indices[3 * t + 2]];
        if (cull.hidden(p0, p1, p2)) continue;
        const size_t before = out.scene.triangle_count();
        out.scene.add_triangle(p0, p1, p2, Vec3(0, 0, 1), Vec3(0, 0, 1), Vec3(0, 0, 1), 0);
        if (out.scene.triangle_count() == before) continue;  // zero area: dropped
        const Vec3 n = out.scene.geometric_normal(before);
        const float towards_eye = perspective ? dot(n, view.eye - p0) : -dot(n, view.forward);
        out.sign.push_back(towards_eye > 0.0f ? 1 : -1);
      }
    };
    add(v.side_begin(), v.side_triangles);
    if (options.near_caps) add(v.near_cap_begin(), v.near_cap_triangles);
    if (options.far_caps) add(v.far_cap_begin(), v.far_cap_triangles);
  }
  return out;
}

// Per-band accumulators: `rows` full-width rows, padded to whole batches of 8. Keys grow
// towards the viewer (raster_setup.h): the nearest surface has the largest key.
struct BandTarget {
  static constexpr int kBlock = 64;  // pixels per depth-cull block of a row
  int stride = 0, rows = 0, blocks = 0;
  std::vector<float> nearest, farthest, crossings;  // crossings: signed counts, exact in float
  std::vector<float> limit;        // key of the biased opaque depth: surfaces need key > limit
  std::vector<float> block_limit;  // the smallest limit of each block of each row

  void reset(int width, int band_rows) {
    stride = (width + 15) & ~7;  // a whole batch beyond the last pixel
    rows = band_rows;
    blocks = (width + kBlock - 1) / kBlock;
    const size_t n = size_t(stride) * size_t(rows);
    nearest.assign(n, -kInfinity);
    farthest.assign(n, kInfinity);
    crossings.assign(n, 0.0f);
    limit.assign(n, kInfinity);
    block_limit.assign(size_t(blocks) * size_t(rows), kInfinity);
  }
  // The farthest opaque surface (smallest limit) of row `row` over pixels [x0, x1).
  float span_limit(int row, int x0, int x1) const {
    const float* b = block_limit.data() + size_t(row) * size_t(blocks);
    return *std::min_element(b + x0 / kBlock, b + (x1 - 1) / kBlock + 1);
  }
};

inline float depth_to_key(float depth, bool perspective) { return perspective ? 1.0f / depth : -depth; }
inline float key_to_depth(float key, bool perspective) { return perspective ? 1.0f / key : -key; }

// Narrows [*x0, *x1) to the pixels of one row that can be covered. Side quads are long
// slivers whose bounding boxes span much of the screen, so testing every pixel of the box
// costs ~20x the covered area. Each edge function is linear in x along the row, so it
// bounds x on one side; the bound is widened by a pixel and every pixel inside is still
// tested exactly, so coverage is unchanged. False when the row is empty.
// inv_dy: 1 / dy of each edge, once per triangle (the crossing only bounds the span, so the
// reciprocal's extra rounding, far below the one-pixel widening, is harmless).
bool row_span(const raster::ScreenTri& tri, const std::array<float, 3>& inv_dy, std::array<float, 3> r, int* x0,
              int* x1) {
  for (int i = 0; i < 3; ++i) {
    const float dy = tri.dy[i];
    if (dy == 0.0f) {  // e = -r along the whole row
      if (!raster::covered(-r[size_t(i)], tri.tie[i])) return false;
      continue;
    }
    // e = 0 at px = cross; clamped to the screen's neighbourhood before converting to int.
    const float cross = std::clamp(tri.ax[i] + r[size_t(i)] * inv_dy[size_t(i)], -1.0e6f, 1.0e6f);
    if (!std::isfinite(cross)) continue;  // cannot narrow; the exact tests still decide
    if (dy > 0.0f)
      *x0 = std::max(*x0, int(std::floor(cross - 0.5f)) - 1);
    else
      *x1 = std::min(*x1, int(std::ceil(cross - 0.5f)) + 2);
  }
  return *x0 < *x1;
}

// The pixels of one row a triangle may count at: [*x0, *x1) narrowed by row_span() and by a
// depth cull against the row's farthest opaque surface under the span (the key is linear along
// the row, so its largest value over the span is at an end; most of a volume lies under the
// ground, behind every pixel). False when none.
bool row_pixels(const raster::ScreenTri& tri, const std::array<float, 3>& inv_dy, float py, const BandTarget& t,
                int row, std::array<float, 3>* r, int* x0, int* x1) {
  *r = raster::row_terms(tri, py);
  if (!row_span(tri, inv_dy, *r, x0, x1)) return false;
  const float best = std::max(raster::key_at(tri, *r, float(*x0) + 0.5f), raster::key_at(tri, *r, float(*x1) - 0.5f));
  return best + 1e-5f * std::abs(best) > t.span_limit(row, *x0, *x1);
}

// One pixel row of a triangle: each covered pixel in front of the opaque surface widens the
// pixel's key range and adds the triangle's sign to its crossings. The 8-lane walk gives the
// same buffers as the scalar one (raster_row.h).
void raster_row_scalar(const raster::ScreenTri& tri, float sign, const std::array<float, 3>& r, int x0, int x1,
                       size_t row, BandTarget& t) {
  raster::for_covered_pixels(tri, r, x0, x1, [&](int x, float key) {
    const size_t i = row + size_t(x);
    if (!(key > t.limit[i])) return;  // at or behind the opaque surface
    t.nearest[i] = std::max(t.nearest[i], key);
    t.farthest[i] = std::min(t.farthest[i], key);
    t.crossings[i] += sign;
  });
}

void raster_row_simd(const raster::ScreenTri& tri, float sign, const std::array<float, 3>& r, int x0, int x1,
                     size_t row, BandTarget& t) {
  using raster::Batch;
  const Batch step(sign), zero(0.0f);
  raster::for_covered_lanes(tri, r, x0, x1, [&](int x, Batch key, raster::Mask mask) {
    const size_t i = row + size_t(x);
    mask = mask & (key > Batch::load_unaligned(&t.limit[i]));
    if (!xsimd::any(mask)) return;
    const Batch nearest = Batch::load_unaligned(&t.nearest[i]), farthest = Batch::load_unaligned(&t.farthest[i]);
    xsimd::select(mask, xsimd::max(nearest, key), nearest).store_unaligned(&t.nearest[i]);
    xsimd::select(mask, xsimd::min(farthest, key), farthest).store_unaligned(&t.farthest[i]);
    (Batch::load_unaligned(&t.crossings[i]) + xsimd::select(mask, step, zero)).store_unaligned(&t.crossings[i]);
  });
}

// One band of rows [y0, y1): every triangle overlapping it, row by row. Bands rather than the
// set-up's 64x64 tiles: side quads are long slivers whose bounding boxes cover many tiles, so a
// tile loop visits each sliver row once per tile it crosses (and one tile, where the silhouette
// bunches up on screen, held half the work); a full-width band visits each row once.
void raster_band(const raster::Setup& s, const VolumeScene& vs, int y0, int y1, BandTarget& t, bool simd) {
  for (const raster::ScreenTri& tri : s.tris) {
    const int ty0 = std::max(tri.y0, y0), ty1 = std::min(tri.y1, y1);
    if (ty0 >= ty1 || tri.x0 >= tri.x1) continue;
    const float sign = float(vs.sign[tri.source]);
    const std::array<float, 3> inv_dy = {1.0f / tri.dy[0], 1.0f / tri.dy[1], 1.0f / tri.dy[2]};
    for (int y = ty0; y < ty1; ++y) {
      std::array<float, 3> r;
      int x0 = tri.x0, x1 = tri.x1;
      if (!row_pixels(tri, inv_dy, float(y) + 0.5f, t, y - y0, &r, &x0, &x1)) continue;
      const size_t row = size_t(y - y0) * size_t(t.stride);
      if (simd)
        raster_row_simd(tri, sign, r, x0, x1, row, t);
      else
        raster_row_scalar(tri, sign, r, x0, x1, row, t);
    }
  }
}

}  // namespace

ShadowVolumeBuffers rasterize_shadow_volumes(std::span<const ShadowVolume> volumes, const View& view,
                                             const Plane& opaque_depth, const ShadowVolumeOptions& options) {
  const int w = view.resolution.x, h = view.resolution.y;
  if (opaque_depth.width != w || opaque_depth.height != h)
    throw std::invalid_argument("rasterize_shadow_volumes: opaque depth size differs from the view's");
  ShadowVolumeBuffers out;
  out.front = Plane(w, h, kNoShadowVolume);
  out.back = Plane(w, h, kNoShadowVolume);
  out.tail_count.assign(size_t(w) * size_t(h), 0);
  for (const ShadowVolume& v : volumes) out.eye_count += volumes_containing(v, view.eye);

  const float keep = 1.0f - options.depth_bias;
  const VolumeScene vs = gather_triangles(volumes, view, options, DepthCull(view, opaque_depth, keep));
  const raster::Setup s = raster::setup_triangles(vs.scene, view, false);
  const bool perspective = s.perspective;
  // About 64 bands (the thread pool balances them), at least 4 rows each.
  const int band_rows = std::max(4, (h + 63) / 64);
  parallel_for((h + band_rows - 1) / band_rows, [&](int band) {
    const int y0 = band * band_rows, y1 = std::min(y0 + band_rows, h);
    thread_local BandTarget t;
    t.reset(w, y1 - y0);
    for (int y = y0; y < y1; ++y) {
      float* limit = &t.limit[size_t(y - y0) * size_t(t.stride)];
      for (int x = 0; x < w; ++x) limit[x] = depth_to_key(opaque_depth.at(x, y) * keep, perspective);
      for (int b = 0; b < t.blocks; ++b)
        t.block_limit[size_t(y - y0) * size_t(t.blocks) + size_t(b)] =
            *std::min_element(limit + b * BandTarget::kBlock, limit + std::min(w, (b + 1) * BandTarget::kBlock));
    }
    raster_band(s, vs, y0, y1, t, options.simd);
    for (int y = y0; y < y1; ++y)
      for (int x = 0; x < w; ++x) {
        const size_t i = size_t(y - y0) * size_t(t.stride) + size_t(x);
        const size_t pixel = size_t(y) * size_t(w) + size_t(x);
        out.tail_count[pixel] = out.eye_count + int32_t(t.crossings[i]);
        float front = kNoShadowVolume, back = kNoShadowVolume;
        if (t.nearest[i] > -kInfinity) {
          const float per_t = view.depth_per_t(view.ray({float(x) + 0.5f, float(y) + 0.5f}).direction);
          front = key_to_depth(t.nearest[i], perspective) / per_t;
          back = key_to_depth(t.farthest[i], perspective) / per_t;
        }
        if (out.eye_count > 0) {
          front = 0.0f;
          if (back == kNoShadowVolume) back = 0.0f;
        }
        out.front.at(x, y) = front;
        out.back.at(x, y) = back;
      }
  });
  return out;
}

}  // namespace caligo
