// The tile loop of the software rasteriser: per 64 x 64 tile, the binned triangles' edge
// functions are evaluated at 8 pixel centres at once (xsimd, AVX2) or one at a time (the
// scalar reference path), with a depth test on a key that grows towards the viewer
// (1/z for perspective views, which interpolates linearly in screen space, or -z for
// orthographic ones). The G-buffer keeps the winning triangle per pixel and resolves its
// shading normal afterwards, so overdraw costs only the depth test.
#include <immintrin.h>
#include <xsimd/xsimd.hpp>

#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include "realtime/raster_row.h"

namespace caligo {
namespace {

using raster::ScreenTri;
using raster::Setup;
using raster::Batch;
using IntBatch = xsimd::batch<int32_t>;

// One tile's depth keys and triangle ids, local to the thread running it (L1/L2 sized), so
// no full-frame scratch buffer is cleared or faulted in per frame.
struct Target {
  static constexpr int stride = raster::kTileSize;
  int x0 = 0, y0 = 0;  // the tile's origin: buffers are indexed (y - y0) * stride + (x - x0)
  alignas(32) float key[raster::kTileSize * raster::kTileSize];
  alignas(32) int32_t id[raster::kTileSize * raster::kTileSize];  // index into Setup::tris, -1 for none

  void reset(const Tile& tile, bool ids) {
    x0 = tile.x0, y0 = tile.y0;
    std::fill(std::begin(key), std::end(key), raster::kEmptyKey);
    if (ids) std::fill(std::begin(id), std::end(id), -1);
  }
  size_t at(int x, int y) const { return size_t(y - y0) * stride + size_t(x - x0); }
};

void raster_tile_scalar(const Setup& s, const Tile& tile, Target& out, bool write_id) {
  for (uint32_t index : s.bins[size_t(tile.index)]) {
    const ScreenTri& t = s.tris[index];
    const int x0 = std::max(t.x0, tile.x0), x1 = std::min(t.x1, tile.x1);
    const int y0 = std::max(t.y0, tile.y0), y1 = std::min(t.y1, tile.y1);
    for (int y = y0; y < y1; ++y) {
      float* key_row = out.key + out.at(out.x0, y);
      raster::for_covered_pixels(t, raster::row_terms(t, float(y) + 0.5f), x0, x1, [&](int x, float key) {
        if (!(key > key_row[x - out.x0])) return;
        key_row[x - out.x0] = key;
        if (write_id) out.id[out.at(x, y)] = int32_t(index);
      });
    }
  }
}

void raster_tile_simd(const Setup& s, const Tile& tile, Target& out, bool write_id) {
  for (uint32_t index : s.bins[size_t(tile.index)]) {
    const ScreenTri& t = s.tris[index];
    const int x0 = std::max(t.x0, tile.x0), x1 = std::min(t.x1, tile.x1);
    const int y0 = std::max(t.y0, tile.y0), y1 = std::min(t.y1, tile.y1);
    // Ids travel as float bit patterns: xsimd 8.1 has no mask cast between float and int.
    const Batch id = xsimd::bitwise_cast<Batch>(IntBatch(int32_t(index)));
    for (int y = y0; y < y1; ++y) {
      float* key_row = out.key + out.at(out.x0, y);
      const auto r = raster::row_terms(t, float(y) + 0.5f);
      raster::for_covered_lanes(t, r, x0, x1, [&](int x, Batch key, raster::Mask mask) {
        const Batch old = Batch::load_aligned(key_row + (x - out.x0));
        mask = mask & (key > old);
        if (!xsimd::any(mask)) return;
        xsimd::select(mask, key, old).store_aligned(key_row + (x - out.x0));
        if (!write_id) return;
        // _mm256_load_ps/_store_ps access memory through may_alias types.
        float* id_row = reinterpret_cast<float*>(out.id + out.at(x, y));
        xsimd::select(mask, id, Batch::load_aligned(id_row)).store_aligned(id_row);
      });
    }
  }
}

inline float key_to_depth(float key, bool perspective) {
  if (perspective) return key > 0.0f ? 1.0f / key : kSkyDepth;
  return key > raster::kEmptyKey ? -key : kSkyDepth;
}

void write_depth(const Setup& s, const Tile& tile, const Target& t, Plane& depth) {
  for (int y = tile.y0; y < tile.y1; ++y) {
    const float* key = t.key + t.at(tile.x0, y);
    float* d = depth.row(y) + tile.x0;
    for (int x = 0; x < tile.x1 - tile.x0; ++x) d[x] = key_to_depth(key[x], s.perspective);
  }
}

// Resolving a pixel: the winning triangle's interpolated shading normal, normalised and
// flipped to the viewer's side of its geometric normal. The scalar and 8-wide versions do
// the same operations in the same order, so either gives the same bits.
struct ResolveContext {
  const RasterScene& scene;
  const View& view;
  const Setup& s;
  float kx, ky;  // tan of the half field of view across x and y (perspective)
};

void resolve_pixel(const ResolveContext& c, const ScreenTri& tri, int x, int y, size_t pixel, GBuffer& g) {
  const float px = float(x) + 0.5f, py = float(y) + 0.5f;
  const float ox = px - tri.ref_x, oy = py - tri.ref_y;
  float f[3];
  for (int k = 0; k < 3; ++k) f[k] = tri.n_base[k] + tri.n_gx[k] * ox + tri.n_gy[k] * oy;
  const Vec3 ng = c.scene.geometric_normal(tri.source);
  Vec3 n = ng;
  const float len2 = f[0] * f[0] + f[1] * f[1] + f[2] * f[2];
  if (len2 > 0.0f) {
    const float inv = 1.0f / std::sqrt(len2);
    n = {f[0] * inv, f[1] * inv, f[2] * inv};
  }
  Vec3 dir = c.view.forward;
  if (c.s.perspective) {
    const float a = (2.0f * px / float(c.s.width) - 1.0f) * c.kx,
                b = (1.0f - 2.0f * py / float(c.s.height)) * c.ky;
    for (int k = 0; k < 3; ++k) dir[k] = c.view.forward[k] + c.view.right[k] * a + c.view.up[k] * b;
  }
  const bool front = ng.x * dir.x + ng.y * dir.y + ng.z * dir.z < 0.0f;
  const float d = n.x * ng.x + n.y * ng.y + n.z * ng.z;
  if (front ? d < 0.0f : d > 0.0f) n = -n;
  g.nx.data[pixel] = n.x;
  g.ny.data[pixel] = n.y;
  g.nz.data[pixel] = n.z;
  g.material[pixel] = c.scene.material(tri.source);
  g.front[pixel] = front ? 1 : 0;
}

void clear_pixel(size_t pixel, GBuffer& g) {
  g.nx.data[pixel] = g.ny.data[pixel] = g.nz.data[pixel] = 0.0f;
  g.material[pixel] = -1;
  g.front[pixel] = 0;
}

// Eight pixels of one triangle (the common case inside a surface).
void resolve_run8(const ResolveContext& c, const ScreenTri& tri, int x, int y, size_t pixel, GBuffer& g) {
  alignas(32) static constexpr float kLaneCentres[8] = {0.5f, 1.5f, 2.5f, 3.5f, 4.5f, 5.5f, 6.5f, 7.5f};
  const Batch px = Batch(float(x)) + Batch::load_aligned(kLaneCentres);
  const float py = float(y) + 0.5f;
  const Batch ox = px - Batch(tri.ref_x);
  const Batch oy(py - tri.ref_y);
  Batch f[3];
  for (int k = 0; k < 3; ++k) f[k] = Batch(tri.n_base[k]) + Batch(tri.n_gx[k]) * ox + Batch(tri.n_gy[k]) * oy;
  const Vec3 ng = c.scene.geometric_normal(tri.source);
  const Batch len2 = f[0] * f[0] + f[1] * f[1] + f[2] * f[2];
  const auto ok = len2 > Batch(0.0f);
  const Batch inv = Batch(1.0f) / xsimd::sqrt(len2);
  Batch n[3];
  for (int k = 0; k < 3; ++k) n[k] = xsimd::select(ok, f[k] * inv, Batch(ng[k]));
  Batch dir[3] = {Batch(c.view.forward.x), Batch(c.view.forward.y), Batch(c.view.forward.z)};
  if (c.s.perspective) {
    const Batch a = (Batch(2.0f) * px / Batch(float(c.s.width)) - Batch(1.0f)) * Batch(c.kx);
    const float b = (1.0f - 2.0f * py / float(c.s.height)) * c.ky;
    for (int k = 0; k < 3; ++k)
      dir[k] = Batch(c.view.forward[k]) + Batch(c.view.right[k]) * a + Batch(c.view.up[k] * b);
  }
  const auto front = Batch(ng.x) * dir[0] + Batch(ng.y) * dir[1] + Batch(ng.z) * dir[2] < Batch(0.0f);
  const Batch d = n[0] * Batch(ng.x) + n[1] * Batch(ng.y) + n[2] * Batch(ng.z);
  const auto back = !front;
  const auto flip = (front & (d < Batch(0.0f))) | (back & (d > Batch(0.0f)));
  for (int k = 0; k < 3; ++k) n[k] = xsimd::select(flip, -n[k], n[k]);
  n[0].store_unaligned(g.nx.data.data() + pixel);
  n[1].store_unaligned(g.ny.data.data() + pixel);
  n[2].store_unaligned(g.nz.data.data() + pixel);
  xsimd::batch<int32_t>(c.scene.material(tri.source)).store_unaligned(g.material.data() + pixel);
  const int front_mask = _mm256_movemask_ps(front);  // xsimd 8.1 has no mask extraction
  for (int i = 0; i < 8; ++i) g.front[pixel + size_t(i)] = uint8_t((front_mask >> i) & 1);
}

void resolve_tile(const ResolveContext& c, const Tile& tile, const Target& t, bool simd, GBuffer& g) {
  for (int y = tile.y0; y < tile.y1; ++y) {
    const int32_t* ids = t.id + t.at(tile.x0, y);
    const size_t row = size_t(y) * size_t(c.s.width);
    int x = tile.x0;
    if (simd) {
      for (; x + 8 <= tile.x1; x += 8) {
        const int32_t* run = ids + (x - tile.x0);
        const bool same =
            run[0] >= 0 && std::all_of(run + 1, run + 8, [&](int32_t v) { return v == run[0]; });
        if (!same) {
          for (int i = 0; i < 8; ++i) {
            if (run[i] < 0)
              clear_pixel(row + size_t(x + i), g);
            else
              resolve_pixel(c, c.s.tris[size_t(run[i])], x + i, y, row + size_t(x + i), g);
          }
          continue;
        }
        resolve_run8(c, c.s.tris[size_t(run[0])], x, y, row + size_t(x), g);
      }
    }
    for (; x < tile.x1; ++x) {
      const int32_t id = ids[x - tile.x0];
      if (id < 0)
        clear_pixel(row + size_t(x), g);
      else
        resolve_pixel(c, c.s.tris[size_t(id)], x, y, row + size_t(x), g);
    }
  }
}

void raster_tile(const Setup& s, const Tile& tile, Target& t, bool write_id, bool simd) {
  if (simd)
    raster_tile_simd(s, tile, t, write_id);
  else
    raster_tile_scalar(s, tile, t, write_id);
}

}  // namespace

Plane rasterize_depth(const RasterScene& scene, const View& view, bool simd, int32_t skip_emitter) {
  const Setup s = raster::setup_triangles(scene, view, false, skip_emitter);
  Plane depth(s.width, s.height);
  parallel_for_tiles(make_tiles(view.resolution, raster::kTileSize), [&](const Tile& tile) {
    thread_local Target t;
    t.reset(tile, false);
    raster_tile(s, tile, t, false, simd);
    write_depth(s, tile, t, depth);
  });
  return depth;
}

void rasterize_gbuffer(const RasterScene& scene, const View& view, GBuffer& g, bool simd) {
  const Setup s = raster::setup_triangles(scene, view, true);
  const size_t pixels = size_t(s.width) * size_t(s.height);
  // Every pixel is written below, so storage of the right size is reused as it is.
  for (Plane* p : {&g.depth, &g.nx, &g.ny, &g.nz})
    if (p->width != s.width || p->height != s.height) *p = Plane(s.width, s.height);
  g.material.resize(pixels);
  g.front.resize(pixels);
  const ResolveContext context{scene, view, s, view.tan_half_fov_y * view.aspect, view.tan_half_fov_y};
  parallel_for_tiles(make_tiles(view.resolution, raster::kTileSize), [&](const Tile& tile) {
    thread_local Target t;
    t.reset(tile, true);
    raster_tile(s, tile, t, true, simd);
    write_depth(s, tile, t, g.depth);
    resolve_tile(context, tile, t, simd, g);
  });
}

GBuffer rasterize_gbuffer(const RasterScene& scene, const View& view, bool simd) {
  GBuffer g;
  rasterize_gbuffer(scene, view, g, simd);
  return g;
}

}  // namespace caligo
