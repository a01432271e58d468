// The low-resolution depth the accumulation rays end at and the gather, temporal and upsample
// passes weigh by. Point sampling (the full-resolution pixel under each low-resolution centre)
// loses what is thinner than a block: a 4 cm cable at quarter resolution is hit by one row of
// centres in four, so along most of it the rays march to the wall behind, and the upsample
// finds no tap of the cable's depth and lights it with the fog in front of the wall.
//
// `min_max` keeps the centre where the upsample can already find every depth of the block and
// otherwise stores one of the block's extremes: its nearest depth when some quadrant of the
// block holds a depth that none of that quadrant's four taps explains (an occluder thinner than
// the block), else its farthest when that is missing (a slit). A depth is explained by a tap
// that agrees with it or by lying between the block's centre and a tap (within the agreement
// threshold), as a plane or a gentle curve through them would give, so walls seen edge-on and
// spheres keep their centres and the gather sees a smooth surface.
// Checkerboarded min/max downsampling is the common alternative; it stores an extreme
// everywhere and breaks a gather that follows the depth's slope.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/parallel.h"
#include "realtime/passes.h"

namespace caligo {
namespace {

// Full-resolution columns (rows) [lo, hi) of each low-resolution column (row), never empty,
// and the first of them the upsample blends with the next low-resolution column rather than
// the one before (the first tap of its bilinear footprint is the column itself).
struct Spans {
  std::vector<int> lo, split, hi;
};

Spans spans(int full, int low) {
  Spans s;
  const float ratio = float(full) / float(low), inverse = float(low) / float(full);
  for (int i = 0; i < low; ++i) {
    const int lo = std::min(full - 1, int(float(i) * ratio));
    const int hi = std::clamp(int(float(i + 1) * ratio), lo + 1, full);
    int split = lo;
    // As the upsample computes the footprint: its first tap is floor((f + 0.5) low / full - 0.5).
    while (split < hi && std::clamp(int(std::floor((float(split) + 0.5f) * inverse - 0.5f)), 0, low - 1) != i)
      ++split;
    s.lo.push_back(lo);
    s.split.push_back(split);
    s.hi.push_back(hi);
  }
  return s;
}

Plane centre_depth(const Plane& full_depth, int w, int h) {
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

// The block's full-resolution depths, split by which neighbours the upsample blends them with:
// quadrant [sy][sx] (0: the neighbour before, 1: the one after) and its nearest and farthest.
struct Quadrants {
  float lo[2][2], hi[2][2];
};

Quadrants quadrants(const Plane& full_depth, const Spans& xs, const Spans& ys, int x, int y) {
  Quadrants q;
  for (int i = 0; i < 4; ++i) {
    q.lo[i / 2][i % 2] = kInfinity;
    q.hi[i / 2][i % 2] = -kInfinity;
  }
  const size_t bx = size_t(x), by = size_t(y);
  const int x0 = xs.lo[bx], xm = xs.split[bx], x1 = xs.hi[bx];
  for (int fy = ys.lo[by]; fy < ys.hi[by]; ++fy) {
    const int sy = fy >= ys.split[by] ? 1 : 0;
    const float* row = full_depth.row(fy);
    float lo0 = q.lo[sy][0], hi0 = q.hi[sy][0], lo1 = q.lo[sy][1], hi1 = q.hi[sy][1];
    for (int fx = x0; fx < xm; ++fx) {
      lo0 = std::min(lo0, row[fx]);
      hi0 = std::max(hi0, row[fx]);
    }
    for (int fx = xm; fx < x1; ++fx) {
      lo1 = std::min(lo1, row[fx]);
      hi1 = std::max(hi1, row[fx]);
    }
    q.lo[sy][0] = lo0;
    q.hi[sy][0] = hi0;
    q.lo[sy][1] = lo1;
    q.hi[sy][1] = hi1;
  }
  return q;
}

// Is depth v what the upsample can find in the footprint of quadrant (sx, sy) of block (x, y)
// with the block holding its centre c and the neighbours `values`: a tap that agrees with it,
// or v between c and another tap (a plane or a gentle curve through them), within the
// relative threshold?
bool explained(const Plane& values, int x, int y, float c, int sx, int sy, float v, float threshold) {
  const int nx = std::clamp(x + (sx ? 1 : -1), 0, values.width - 1);
  const int ny = std::clamp(y + (sy ? 1 : -1), 0, values.height - 1);
  const float slack = threshold * v;
  const float n[3] = {nx == x ? c : values.at(nx, y), ny == y ? c : values.at(x, ny),
                      nx == x && ny == y ? c : values.at(nx, ny)};
  if (std::abs(v - c) <= slack) return true;
  for (float t : n)
    if (v >= std::min(c, t) - slack && v <= std::max(c, t) + slack) return true;
  return false;
}

// What block (x, y) stores, its neighbours holding `values`: its centre where that leaves
// none of its depths unexplained, else its nearest depth (an occluder left out lets the fog
// behind it leak onto it), else its farthest.
float block_depth(const Plane& full_depth, const Spans& xs, const Spans& ys, const Plane& values, float c, int x,
                  int y, float threshold) {
  const Quadrants q = quadrants(full_depth, xs, ys, x, y);
  float lo = kInfinity, hi = -kInfinity;
  for (int i = 0; i < 4; ++i) {
    lo = std::min(lo, q.lo[i / 2][i % 2]);
    hi = std::max(hi, q.hi[i / 2][i % 2]);
  }
  if (std::abs(lo - c) <= threshold * lo && std::abs(hi - c) <= threshold * hi) return c;  // most blocks
  bool near_missing = false, far_missing = false;
  for (int sy = 0; sy < 2; ++sy)
    for (int sx = 0; sx < 2; ++sx) {
      if (q.lo[sy][sx] > q.hi[sy][sx]) continue;  // no pixel on this side (odd scales)
      near_missing |= !explained(values, x, y, c, sx, sy, q.lo[sy][sx], threshold);
      far_missing |= !explained(values, x, y, c, sx, sy, q.hi[sy][sx], threshold);
    }
  return near_missing ? lo : far_missing ? hi : c;
}

}  // namespace

Plane downsample_depth(const Plane& full_depth, int scale, LowResolutionDepth mode, float relative_threshold) {
  // ceil, as the pipeline sizes its low-resolution view: no full-resolution pixel is left
  // without low-resolution pixels over it.
  const int w = std::max(1, (full_depth.width + scale - 1) / scale);
  const int h = std::max(1, (full_depth.height + scale - 1) / scale);
  const Plane centres = centre_depth(full_depth, w, h);
  if (mode == LowResolutionDepth::centre || scale == 1) return centres;
  // First each block against its neighbours' centres (in parallel): most keep their centre.
  // Then, in row order, the blocks that changed and their neighbours are decided again
  // against what the blocks before them hold now and the centres of those after: of two
  // blocks sharing a cable two pixels wide (one row in each) the second keeps its centre, as
  // the first's nearest depth serves it, so the wall beside the cable keeps a tap too. (Deciding
  // against changed neighbours on both sides would let a chain of blocks along a diagonal
  // cable each go back to its centre, trusting the next one.)
  const Spans xs = spans(full_depth.width, w), ys = spans(full_depth.height, h);
  std::vector<uint8_t> revisit(size_t(w) * size_t(h), 0);
  const auto mark_around = [&](int x, int y) {
    for (int ny = std::max(0, y - 1); ny <= std::min(h - 1, y + 1); ++ny)
      for (int nx = std::max(0, x - 1); nx <= std::min(w - 1, x + 1); ++nx) revisit[size_t(ny * w + nx)] = 1;
  };
  parallel_for(h, [&](int y) {
    // The nearest and farthest of each full-resolution column of the block row (vectorised
    // across the row), then of each block: most blocks agree with their centre and stop there.
    const size_t by = size_t(y), fw = size_t(full_depth.width);
    std::vector<float> near(full_depth.row(ys.lo[by]), full_depth.row(ys.lo[by]) + fw), far = near;
    for (int fy = ys.lo[by] + 1; fy < ys.hi[by]; ++fy) {
      const float* row = full_depth.row(fy);
      for (size_t i = 0; i < fw; ++i) {
        near[i] = std::min(near[i], row[i]);
        far[i] = std::max(far[i], row[i]);
      }
    }
    for (int x = 0; x < w; ++x) {
      const float c = centres.at(x, y);
      float lo = kInfinity, hi = -kInfinity;
      for (int i = xs.lo[size_t(x)]; i < xs.hi[size_t(x)]; ++i) {
        lo = std::min(lo, near[size_t(i)]);
        hi = std::max(hi, far[size_t(i)]);
      }
      if (std::abs(lo - c) <= relative_threshold * lo && std::abs(hi - c) <= relative_threshold * hi) continue;
      if (block_depth(full_depth, xs, ys, centres, c, x, y, relative_threshold) != c) revisit[size_t(y * w + x)] = 2;
    }
  });
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (revisit[size_t(y * w + x)] == 2) mark_around(x, y);
  Plane low = centres;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!revisit[size_t(y * w + x)]) continue;
      low.at(x, y) = block_depth(full_depth, xs, ys, low, centres.at(x, y), x, y, relative_threshold);
      if (low.at(x, y) != centres.at(x, y)) mark_around(x, y);
    }
  return low;
}

}  // namespace caligo
