// Internal to the rasteriser (raster_setup.cpp, raster.cpp): triangles projected, clipped
// and binned into screen tiles for one view.
//
// Watertightness without fixed point: every edge is evaluated in a canonical direction
// (from its lexicographically smaller screen vertex), so the two triangles sharing an edge
// compute exactly negated edge values at every pixel centre (IEEE negation and x * -y are
// exact). A pixel centre exactly on the edge belongs to the triangle that traverses the edge
// in its canonical direction, so it is covered once: no cracks, no double blending. This
// replaces the top-left rule, which needs exact (fixed-point) edge values.
// raster_setup.cpp and raster.cpp are compiled with -ffp-contract=off so that the SIMD and
// scalar loops round identically.
#pragma once

#include <cstdint>
#include <vector>

#include "realtime/scene_buffers.h"

namespace caligo::raster {

inline constexpr int kTileSize = 64;  // pixels; a multiple of the SIMD width 8

// One (possibly clipped) triangle in screen space, positively oriented.
struct ScreenTri {
  // Edge i is opposite vertex i: e_i(p) = (p.x - ax) * dy - (p.y - ay) * dx, >= 0 inside.
  float ax[3], ay[3], dx[3], dy[3];
  bool tie[3];  // a pixel centre with e_i == 0 is covered
  // Depth key (larger = nearer): key = e0 c0 + e1 c1 + e2 c2. 1/z (perspective) or -z.
  float c[3];
  int x0, y0, x1, y1;  // conservative pixel bounds, half-open, inside the viewport
  uint32_t source;     // triangle index in the RasterScene
  // Shading-normal planes (G-buffer only): n_k * w is affine in screen space, w = 1/z
  // (perspective) or 1; n_k ~ base[k] + gx[k] (x - ref_x) + gy[k] (y - ref_y).
  float ref_x, ref_y;
  float n_base[3], n_gx[3], n_gy[3];
};

struct Setup {
  int width = 0, height = 0;
  int tiles_x = 0, tiles_y = 0;
  bool perspective = true;
  std::vector<ScreenTri> tris;
  std::vector<std::vector<uint32_t>> bins;  // per tile, indices into tris in scene order
};

// Projects, clips (near plane and a guard band) and bins every triangle. With
// `attributes`, also fills the normal planes.
Setup setup_triangles(const RasterScene& scene, const View& view, bool attributes, int32_t skip_emitter = -1);

// The depth key's value for "nothing here".
inline constexpr float kEmptyKey = -3.0e38f;

}  // namespace caligo::raster
