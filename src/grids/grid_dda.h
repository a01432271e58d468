// A 3D DDA over a dense lattice of unit cells (Amanatides & Woo 1987): the block traversal's
// two levels (grids/grid_traversal.cpp) and the emission sampler's walk over emissive blocks
// (volumes/emission_sampler.cpp).
#pragma once

#include <algorithm>
#include <cmath>

#include "core/math.h"
#include "core/vec.h"

namespace caligo {

// Visits the unit cells [0, n)^3 crossed by x(t) = o + t d over [ta, tb], in order, with the
// t range inside each; the ranges tile [ta, tb] exactly (the last cell ends at tb even when
// rounding puts the final crossing a hair early). `visit(cell, t_enter, t_exit)`.
template <class Visit>
void for_each_lattice_cell(Vec3 o, Vec3 d, float ta, float tb, const int n[3], Visit&& visit) {
  int cell[3], step[3];
  float next[3], inv[3];
  for (int a = 0; a < 3; ++a) {
    const float p = o[a] + d[a] * ta;
    cell[a] = int(std::floor(std::clamp(p, 0.0f, float(n[a]) - 0.5f)));
    // A component so small that 1/d overflows never crosses a cell within float range of t;
    // stepping on it would make next = 0 * inf = NaN on a cell face and derail the axis choice.
    inv[a] = 1.0f / d[a];
    step[a] = !std::isfinite(inv[a]) ? 0 : (d[a] > 0.0f ? 1 : -1);
    if (step[a] == 0) inv[a] = 0.0f;
    next[a] = step[a] != 0 ? (float(cell[a] + (step[a] > 0)) - o[a]) * inv[a] : kInfinity;
  }
  float t = ta;
  for (;;) {
    const int axis = next[0] < next[1] ? (next[0] < next[2] ? 0 : 2) : (next[1] < next[2] ? 1 : 2);
    const int moved = cell[axis] + step[axis];
    const bool last = !(next[axis] < tb) || moved < 0 || moved >= n[axis];
    const float t_exit = last ? tb : std::max(next[axis], t);
    visit(cell, t, t_exit);
    if (last) return;
    cell[axis] = moved;
    next[axis] = (float(moved + (step[axis] > 0)) - o[axis]) * inv[axis];
    t = t_exit;
  }
}

}  // namespace caligo
