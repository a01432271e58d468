// One pixel row of a set-up triangle (raster_setup.h): the edge functions at the row's pixel
// centres, the coverage rule and the depth key, written once for the rasteriser's tiles
// (raster.cpp) and the shadow-volume bands (hybrid/shadow_volume_raster.cpp). Each caller passes what
// it does with a covered pixel: a depth test, a crossing count.
//
// The scalar and 8-lane walks do the same operations in the same order; the files including
// this header are compiled with -ffp-contract=off, so both give the same bits.
#pragma once

#include <xsimd/xsimd.hpp>

#include <array>

#include "realtime/raster_setup.h"

namespace caligo::raster {

using Batch = xsimd::batch<float>;
using Mask = xsimd::batch_bool<float>;
static_assert(Batch::size == 8, "the row walks assume 8 lanes (AVX2)");

inline bool covered(float e, bool tie) { return e > 0.0f || (e == 0.0f && tie); }
inline Mask covered(Batch e, bool tie) { return tie ? (e >= Batch(0.0f)) : (e > Batch(0.0f)); }

// The row terms of the three edge functions at pixel row centre py: e_i = (px - ax_i) dy_i - r_i.
inline std::array<float, 3> row_terms(const ScreenTri& t, float py) {
  return {(py - t.ay[0]) * t.dx[0], (py - t.ay[1]) * t.dx[1], (py - t.ay[2]) * t.dx[2]};
}

// The depth key at pixel centre px of the row (whether or not it is covered).
inline float key_at(const ScreenTri& t, const std::array<float, 3>& r, float px) {
  return ((px - t.ax[0]) * t.dy[0] - r[0]) * t.c[0] + ((px - t.ax[1]) * t.dy[1] - r[1]) * t.c[1] +
         ((px - t.ax[2]) * t.dy[2] - r[2]) * t.c[2];
}

// visit(x, key) for every covered pixel x of [x0, x1).
template <typename Visit>
void for_covered_pixels(const ScreenTri& t, const std::array<float, 3>& r, int x0, int x1, Visit&& visit) {
  for (int x = x0; x < x1; ++x) {
    const float px = float(x) + 0.5f;
    const float e0 = (px - t.ax[0]) * t.dy[0] - r[0];
    const float e1 = (px - t.ax[1]) * t.dy[1] - r[1];
    const float e2 = (px - t.ax[2]) * t.dy[2] - r[2];
    if (!covered(e0, t.tie[0]) || !covered(e1, t.tie[1]) || !covered(e2, t.tie[2])) continue;
    visit(x, e0 * t.c[0] + e1 * t.c[1] + e2 * t.c[2]);
  }
}

// visit(x, keys, mask) for each run of 8 pixels from x0 & ~7 on (x a multiple of 8) with a
// covered pixel of [x0, x1): lanes outside [x0, x1) are masked, so the walk tests exactly the
// pixels for_covered_pixels does.
template <typename Visit>
void for_covered_lanes(const ScreenTri& t, const std::array<float, 3>& r, int x0, int x1, Visit&& visit) {
  alignas(32) static constexpr float kLaneCentres[8] = {0.5f, 1.5f, 2.5f, 3.5f, 4.5f, 5.5f, 6.5f, 7.5f};
  const Batch lanes = Batch::load_aligned(kLaneCentres);
  const Batch lo = Batch(float(x0)), hi = Batch(float(x1));
  const Batch ax0(t.ax[0]), ax1(t.ax[1]), ax2(t.ax[2]);
  const Batch dy0(t.dy[0]), dy1(t.dy[1]), dy2(t.dy[2]);
  const Batch c0(t.c[0]), c1(t.c[1]), c2(t.c[2]);
  const Batch r0(r[0]), r1(r[1]), r2(r[2]);
  for (int x = x0 & ~7; x < x1; x += 8) {
    const Batch px = Batch(float(x)) + lanes;
    const Batch e0 = (px - ax0) * dy0 - r0;
    const Batch e1 = (px - ax1) * dy1 - r1;
    const Batch e2 = (px - ax2) * dy2 - r2;
    const Mask mask =
        covered(e0, t.tie[0]) & covered(e1, t.tie[1]) & covered(e2, t.tie[2]) & (px > lo) & (px < hi);
    if (!xsimd::any(mask)) continue;
    visit(x, e0 * c0 + e1 * c1 + e2 * c2, mask);
  }
}

}  // namespace caligo::raster
