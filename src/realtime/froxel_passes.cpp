// The froxel grid's image-to-image passes: reprojection of the previous grid, front-to-back
// integration per column, and the per-pixel lookup (froxel_fog.h). Each touches every froxel
// or pixel once per frame, so the transcendental functions are taken 8 lanes at a time and
// the inner loops read contiguous memory.
#include <xsimd/xsimd.hpp>

#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include "realtime/froxel_fog.h"
#include "realtime/light_profile_simd.h"
#include "realtime/scene_buffers.h"

namespace caligo {
namespace {

using Batch = xsimd::batch<float>;
constexpr int kLanes = int(Batch::size);

// FroxelGrid::edge_coordinate of n depths, 8 at a time.
void edge_coordinates(const FroxelGrid& g, const float* z, int n, float* out) {
  const float scale = float(g.slices - 1) / std::log(g.far / g.near), inv_near = 1.0f / g.near;
  int i = 0;
  for (; i + kLanes <= n; i += kLanes) {
    const Batch d = Batch::load_unaligned(z + i) * inv_near;
    const Batch near_part = xsimd::max(d, Batch(0.0f));
    const Batch far_part = xsimd::min(1.0f + scale * xsimd::log(xsimd::max(d, Batch(1.0f))), Batch(float(g.slices)));
    xsimd::select(d <= 1.0f, near_part, far_part).store_unaligned(out + i);
  }
  for (; i < n; ++i) out[i] = g.edge_coordinate(z[i]);
}

// Where a trilinear read of the history at continuous cell coordinates (centres at integers,
// clamped to the grid; the caller has checked the point lies in it) takes its 8 corners: the
// slice pairs at p, p + dx, p + dy, p + dx + dy, and the weights.
struct HistoryTaps {
  const Froxel* p;
  size_t dx, dy;
  float fx, fy, fs;
};
HistoryTaps history_taps(const FroxelGrid& g, const Froxel* field, float gx, float gy, float gs) {
  gx = std::clamp(gx, 0.0f, float(g.width - 1));
  gy = std::clamp(gy, 0.0f, float(g.height - 1));
  gs = std::clamp(gs, 0.0f, float(g.slices - 1));
  const int x0 = std::min(int(gx), std::max(0, g.width - 2)), y0 = std::min(int(gy), std::max(0, g.height - 2));
  const int s0 = std::min(int(gs), g.slices - 2);
  return {field + (size_t(y0) * size_t(g.width) + size_t(x0)) * size_t(g.slices) + size_t(s0),
          g.width > 1 ? size_t(g.slices) : 0, g.height > 1 ? size_t(g.width) * size_t(g.slices) : 0,
          gx - float(x0), gy - float(y0), gs - float(s0)};
}

// The history's froxel (both fields) by the taps (the scalar reference).
Froxel sample_history(const FroxelGrid& g, const Froxel* field, float gx, float gy, float gs) {
  const HistoryTaps h = history_taps(g, field, gx, gy, gs);
  Froxel out;
  auto add = [&](const Froxel* q, float w) {
    out.sigma_t += (q[0].sigma_t * (1 - h.fs) + q[1].sigma_t * h.fs) * w;
    out.scatter += (q[0].scatter * (1 - h.fs) + q[1].scatter * h.fs) * w;
  };
  add(h.p, (1 - h.fx) * (1 - h.fy));
  add(h.p + h.dx, h.fx * (1 - h.fy));
  add(h.p + h.dy, (1 - h.fx) * h.fy);
  add(h.p + h.dx + h.dy, h.fx * h.fy);
  return out;
}

// sample_history with the slice pair of each corner column (12 floats, contiguous) read by
// two 8-lane loads: lanes 0..5 hold the six fields of slice s0 and of s0 + 1, lanes 6 and 7
// are the neighbours' and are dropped (FroxelMedia's padding froxel keeps the last pair's
// second load inside the buffer). AVX2 gathers of each field cost more than the arithmetic.
Froxel sample_history_lanes(const FroxelGrid& g, const Froxel* field, float gx, float gy, float gs) {
  const HistoryTaps h = history_taps(g, field, gx, gy, gs);
  auto pair = [&](const Froxel* q) {
    const float* f = reinterpret_cast<const float*>(q);
    const Batch lo = Batch::load_unaligned(f), hi = Batch::load_unaligned(f + 6);
    return lo + (hi - lo) * h.fs;
  };
  const Batch v = (pair(h.p) * (1 - h.fx) + pair(h.p + h.dx) * h.fx) * (1 - h.fy) +
                  (pair(h.p + h.dy) * (1 - h.fx) + pair(h.p + h.dx + h.dy) * h.fx) * h.fy;
  alignas(32) float o[kLanes];
  v.store_aligned(o);
  return {RGB(o[0], o[1], o[2]), RGB(o[3], o[4], o[5])};
}

// One column's blend towards the current frame, old[s] the history at froxel s (used where
// use[s]).
void blend_column(Froxel* cells, const Froxel* old, const uint8_t* use, int n, float blend) {
  for (int s = 0; s < n; ++s) {
    if (!use[s]) continue;
    cells[s].sigma_t = old[s].sigma_t + (cells[s].sigma_t - old[s].sigma_t) * blend;
    cells[s].scatter = old[s].scatter + (cells[s].scatter - old[s].scatter) * blend;
  }
}

// A column's points p = eye_h + a + b z seen from the history view: its depth z0 + z1 z and
// its right and up coordinates, and the factors that take them to history grid coordinates
// (View::project's arithmetic, regrouped).
struct HistoryAxes {
  bool perspective;
  float z0, z1, x0, x1, y0, y1;
  float kx, cx, ky, cy;
};
HistoryAxes history_axes(const View& v, Vec3 a, Vec3 b, float to_x, float to_y) {
  HistoryAxes h;
  h.perspective = v.projection == Projection::perspective;
  h.z0 = dot(a, v.forward), h.z1 = dot(b, v.forward);
  h.x0 = dot(a, v.right), h.x1 = dot(b, v.right);
  h.y0 = dot(a, v.up), h.y1 = dot(b, v.up);
  const float w = 0.5f * float(v.resolution.x) * to_x, hh = 0.5f * float(v.resolution.y) * to_y;
  h.kx = h.perspective ? w / (v.tan_half_fov_y * v.aspect) : w / v.half_width;
  h.ky = -(h.perspective ? hh / v.tan_half_fov_y : hh / v.half_height);
  h.cx = w - 0.5f;
  h.cy = hh - 0.5f;
  return h;
}

bool same_view(const View& a, const View& b) {
  return a.projection == b.projection && a.eye == b.eye && a.forward == b.forward && a.up == b.up &&
         a.resolution == b.resolution &&
         a.tan_half_fov_y == b.tan_half_fov_y && a.aspect == b.aspect && a.half_width == b.half_width &&
         a.half_height == b.half_height;
}

bool same_grid(const FroxelGrid& a, const FroxelGrid& b) {
  return a.width == b.width && a.height == b.height && a.slices == b.slices && a.near == b.near && a.far == b.far;
}

}  // namespace

void reproject_froxels(const FroxelGrid& grid, const View& view, const FroxelMedia& history,
                       const FroxelGrid& history_grid, const View& history_view, float blend,
                       std::span<const uint8_t> fresh, FroxelMedia& current, bool simd) {
  const size_t n = size_t(grid.slices);
  auto keeps_history = [&](size_t i) { return fresh.empty() || !fresh[i]; };
  if (same_grid(grid, history_grid) && same_view(view, history_view)) {
    // A still camera: every froxel's centre is its own in the history.
    parallel_for(grid.height, [&](int y) {
      std::vector<uint8_t> use(n);
      for (int x = 0; x < grid.width; ++x) {
        const size_t first = (size_t(y) * size_t(grid.width) + size_t(x)) * n;
        for (size_t s = 0; s < n; ++s) use[s] = keeps_history(first + s);
        blend_column(current.cells.data() + first, history.cells.data() + first, use.data(), grid.slices, blend);
      }
    });
    return;
  }
  const std::vector<float> edges = slice_edges(grid);
  std::vector<float> centre(n);
  for (size_t s = 0; s < n; ++s) centre[s] = 0.5f * (edges[s] + edges[s + 1]);
  const float to_x = float(history_grid.width) / float(history_view.resolution.x);
  const float to_y = float(history_grid.height) / float(history_view.resolution.y);
  parallel_for(grid.height, [&](int y) {
    std::vector<float> hx(n), hy(n), hz(n), hs(n);
    std::vector<Froxel> old(n);
    std::vector<uint8_t> use(n);
    for (int x = 0; x < grid.width; ++x) {
      // The column's points are affine in depth, a + b z, and so are their coordinates along
      // the history view's axes: the history grid coordinates are ratios of affine functions
      // of z, a loop the compiler vectorises (View::project per point cost a call each).
      const Vec2 film = grid.film(view, float(x), float(y));
      const Vec3 a = view.unproject(film, 0.0f) - history_view.eye, b = view.unproject(film, 1.0f) - a -
                                                                        history_view.eye;
      const HistoryAxes h = history_axes(history_view, a, b, to_x, to_y);
      for (size_t s = 0; s < n; ++s) {
        const float c = centre[s];
        const float z = h.z0 + h.z1 * c;
        const float inv = h.perspective ? 1.0f / z : 1.0f;
        hx[s] = (h.x0 + h.x1 * c) * inv * h.kx + h.cx;
        hy[s] = (h.y0 + h.y1 * c) * inv * h.ky + h.cy;
        hz[s] = z;
      }
      edge_coordinates(history_grid, hz.data(), grid.slices, hs.data());
      const size_t first = (size_t(y) * size_t(grid.width) + size_t(x)) * n;
      size_t s = 0;
      for (; s < n; ++s) {
        // Slice coordinate of the centre: the edge coordinate less half a slice.
        hs[s] -= 0.5f;
        const float gx = hx[s], gy = hy[s], gs = hs[s];
        use[s] = keeps_history(first + s) && hz[s] > 0.0f && gx >= -0.5f && gy >= -0.5f &&
                 gx <= float(history_grid.width) - 0.5f && gy <= float(history_grid.height) - 0.5f &&
                 gs <= float(history_grid.slices) - 0.5f;
      }
      for (s = 0; s < n; ++s) {
        if (!use[s]) continue;
        old[s] = simd ? sample_history_lanes(history_grid, history.cells.data(), hx[s], hy[s], hs[s])
                      : sample_history(history_grid, history.cells.data(), hx[s], hy[s], hs[s]);
      }
      blend_column(current.cells.data() + first, old.data(), use.data(), grid.slices, blend);
    }
  });
}

void integrate_froxels(const FroxelGrid& grid, const FroxelColumns& columns, const FroxelMedia& media,
                       std::vector<RGB>& out) {
  const size_t edges = size_t(grid.slices) + 1;
  const std::vector<float> z = slice_edges(grid);
  out.resize(grid.columns() * edges);
  parallel_for(grid.height, [&](int y) {
    const size_t n = 3 * size_t(grid.slices);
    std::vector<float> optical(n + kLanes), decay(n + kLanes);
    for (int x = 0; x < grid.width; ++x) {
      const size_t c = size_t(y) * size_t(grid.width) + size_t(x);
      const float t_per_depth = columns.columns[c].t_per_depth;
      const Froxel* cells = media.cells.data() + c * size_t(grid.slices);
      for (int s = 0; s < grid.slices; ++s) {
        const float dt = (z[size_t(s) + 1] - z[size_t(s)]) * t_per_depth;
        for (int ch = 0; ch < 3; ++ch) optical[3 * size_t(s) + size_t(ch)] = cells[s].sigma_t[ch] * dt;
      }
      for (size_t i = 0; i < n; i += kLanes) xsimd::exp(-Batch::load_unaligned(&optical[i])).store_unaligned(&decay[i]);
      RGB sum(0.0f), transmittance(1.0f);
      RGB* o = out.data() + c * edges;
      o[0] = sum;
      for (int s = 0; s < grid.slices; ++s) {
        const float dt = (z[size_t(s) + 1] - z[size_t(s)]) * t_per_depth;
        float step_l[3];
        for (int ch = 0; ch < 3; ++ch) {
          // The slice's scatter S integrated: S (1 - e^(-x)) / sigma_t, x = sigma_t dt; its
          // series S dt (1 - x/2 + x^2/6 - x^3/24) where 1 - e^(-x) would lose digits.
          const float x = optical[3 * size_t(s) + size_t(ch)], e = decay[3 * size_t(s) + size_t(ch)];
          const float in = cells[s].scatter[ch];
          const float series = 1.0f - x * (0.5f - x * (1.0f / 6.0f - x * (1.0f / 24.0f)));
          step_l[ch] = in * (x > 1e-2f ? (1.0f - e) * dt / x : dt * series);
        }
        sum += transmittance * RGB(step_l[0], step_l[1], step_l[2]);
        transmittance *= RGB(decay[3 * size_t(s)], decay[3 * size_t(s) + 1], decay[3 * size_t(s) + 2]);
        o[s + 1] = sum;
      }
    }
  });
}

namespace {

// One output row's lookup: its two grid rows, and per output x the columns and weights.
struct LookupRow {
  const RGB* base;         // the integrated grid
  const RGB *row0, *row1;  // the integrated edges of grid rows y0 and y1
  float fy;
  size_t edges;            // slices + 1
  int last_slice;          // slices - 1
  const float* e;          // edge coordinate of each pixel's depth
  const int *x0s, *x1s;
  const float* fxs;

  // 8 pixels from x: the four columns' two edges around each depth by AVX2 gathers (24 a
  // batch: FroxelLookup::gathers, the former lookup, kept for the benchmark's ratio).
  void lanes(int x, float* r, float* g, float* b) const {
    using IBatch = xsimd::batch<int32_t>;
    const Batch ev = Batch::load_unaligned(e + x);
    const IBatch e0 = xsimd::min(xsimd::batch_cast<int32_t>(ev), IBatch(last_slice));
    const Batch fe = ev - xsimd::batch_cast<float>(e0), fx = Batch::load_unaligned(fxs + x);
    const IBatch i0 = (IBatch::load_unaligned(x0s + x) * int32_t(edges) + e0) * 3;
    const IBatch i1 = (IBatch::load_unaligned(x1s + x) * int32_t(edges) + e0) * 3;
    const float* f0 = reinterpret_cast<const float*>(row0);
    const float* f1 = reinterpret_cast<const float*>(row1);
    auto at = [&](const float* f, const IBatch& i, int ch) {
      const Batch lo = profile_simd::gather(f + ch, i), hi = profile_simd::gather(f + ch + 3, i);
      return lo + (hi - lo) * fe;
    };
    auto channel = [&](int ch) {
      const Batch top = at(f0, i0, ch) * (1.0f - fx) + at(f0, i1, ch) * fx;
      const Batch bottom = at(f1, i0, ch) * (1.0f - fx) + at(f1, i1, ch) * fx;
      return top * (1.0f - fy) + bottom * fy;
    };
    channel(0).store_unaligned(r + x);
    channel(1).store_unaligned(g + x);
    channel(2).store_unaligned(b + x);
  }

  // One pixel from x by four 8-float loads, one per column around it: each load holds the
  // column's two edges around the depth (RGB at e0 in lanes 0..2, at e0 + 1 in 3..5), so the
  // bilinear blend is four multiply-adds across lanes and the edge blend one shuffle. Where
  // the last load would run past `size` floats, the scalar pixel.
  RGB pixel_loads(int x, size_t size) const {
    const int e0 = std::min(int(e[x]), last_slice);
    const float fe = e[x] - float(e0), fx = fxs[x];
    const size_t o0 = (size_t(x0s[x]) * edges + size_t(e0)) * 3, o1 = (size_t(x1s[x]) * edges + size_t(e0)) * 3;
    const size_t row_floats = size_t(row1 - row0) * 3;
    if (std::max(o0, o1) + row_floats + kLanes > size - size_t(row0 - base) * 3) return pixel(x);
    const float* f0 = reinterpret_cast<const float*>(row0);
    const float* f1 = reinterpret_cast<const float*>(row1);
    const Batch top = Batch::load_unaligned(f0 + o0) * (1.0f - fx) + Batch::load_unaligned(f0 + o1) * fx;
    const Batch bottom = Batch::load_unaligned(f1 + o0) * (1.0f - fx) + Batch::load_unaligned(f1 + o1) * fx;
    alignas(32) float v[kLanes];
    (top * (1.0f - fy) + bottom * fy).store_aligned(v);
    return {v[0] + (v[3] - v[0]) * fe, v[1] + (v[4] - v[1]) * fe, v[2] + (v[5] - v[2]) * fe};
  }

  RGB pixel(int x) const {
    const int e0 = std::min(int(e[x]), last_slice);
    const float fe = e[x] - float(e0), fx = fxs[x];
    auto column = [&](const RGB* row, int cx) {
      const RGB* o = row + size_t(cx) * edges + size_t(e0);
      return o[0] + (o[1] - o[0]) * fe;
    };
    return (column(row0, x0s[x]) * (1.0f - fx) + column(row0, x1s[x]) * fx) * (1.0f - fy) +
           (column(row1, x0s[x]) * (1.0f - fx) + column(row1, x1s[x]) * fx) * fy;
  }
};

}  // namespace

void lookup_froxels(const FroxelGrid& grid, std::span<const RGB> integrated, const Plane& depth, ColorPlanes& out,
                    FroxelLookup method) {
  if (out.width() != depth.width || out.height() != depth.height) out = ColorPlanes(depth.width, depth.height);
  const size_t edges = size_t(grid.slices) + 1;
  const float sx = float(grid.width) / float(depth.width), sy = float(grid.height) / float(depth.height);
  // The columns and weights of each output x, shared by every row.
  std::vector<int> x0s(size_t(depth.width)), x1s(size_t(depth.width));
  std::vector<float> fxs(size_t(depth.width));
  for (int x = 0; x < depth.width; ++x) {
    const float gx = std::clamp((float(x) + 0.5f) * sx - 0.5f, 0.0f, float(grid.width - 1));
    x0s[size_t(x)] = int(gx);
    x1s[size_t(x)] = std::min(int(gx) + 1, grid.width - 1);
    fxs[size_t(x)] = gx - float(int(gx));
  }
  parallel_for(depth.height, [&](int y) {
    const float gy = std::clamp((float(y) + 0.5f) * sy - 0.5f, 0.0f, float(grid.height - 1));
    const int y0 = int(gy), y1 = std::min(y0 + 1, grid.height - 1);
    std::vector<float> e(size_t(depth.width)), d(depth.row(y), depth.row(y) + depth.width);
    for (float& v : d) v = v >= kSkyDepth ? grid.far : v;
    edge_coordinates(grid, d.data(), depth.width, e.data());
    const LookupRow row{integrated.data(), integrated.data() + size_t(y0) * size_t(grid.width) * edges,
                        integrated.data() + size_t(y1) * size_t(grid.width) * edges,
                        gy - float(y0), edges, grid.slices - 1, e.data(), x0s.data(), x1s.data(), fxs.data()};
    float *r = out.r.row(y), *g = out.g.row(y), *b = out.b.row(y);
    int x = 0;
    if (method == FroxelLookup::gathers)
      for (; x + kLanes <= depth.width; x += kLanes) row.lanes(x, r, g, b);
    const size_t size = integrated.size() * 3;
    for (; x < depth.width; ++x) {
      const RGB v = method == FroxelLookup::loads ? row.pixel_loads(x, size) : row.pixel(x);
      r[x] = v.r;
      g[x] = v.g;
      b[x] = v.b;
    }
  });
}

}  // namespace caligo
