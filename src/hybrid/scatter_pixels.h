// What the scattering passes of hybrid/ share: the per-pixel jitter and the parallel loop that
// fills a ScatterResult (radiance and shadow-map lookups per pixel, and their totals).
#pragma once

#include <cmath>
#include <cstdint>

#include "core/parallel.h"
#include "hybrid/hybrid_scatter.h"

namespace caligo::scatter_pixels {

// Jimenez's interleaved gradient noise: a per-pixel offset in [0, 1) whose neighbours differ
// enough that a 3x3 blur averages the step pattern away.
inline float pixel_noise(int x, int y) {
  const float f = 0.06711056f * float(x) + 0.00583715f * float(y);
  const float g = 52.9829189f * (f - std::floor(f));
  return g - std::floor(g);
}

// Runs body(x, y, lookups&) -> RGB for every pixel, rows in parallel.
template <typename Body>
ScatterResult for_each_pixel(const View& view, const Body& body) {
  const int w = view.resolution.x, h = view.resolution.y;
  ScatterResult result;
  result.radiance = ColorPlanes(w, h);
  result.lookups.assign(size_t(w) * size_t(h), 0);
  parallel_for(h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      int32_t& lookups = result.lookups[size_t(y) * size_t(w) + size_t(x)];
      result.radiance.set(x, y, body(x, y, lookups));
    }
  });
  for (int32_t n : result.lookups) {
    result.total_lookups += n;
    result.marched_pixels += n > 0;
  }
  return result;
}

}  // namespace caligo::scatter_pixels
