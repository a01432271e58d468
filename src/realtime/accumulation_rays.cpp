#include "realtime/accumulation_rays.h"

#include <algorithm>

#include "core/parallel.h"
#include "realtime/interleave.h"

namespace caligo {

void AccumulationRays::build(const VolumeScene& volumes, const View& view, const Plane& depth,
                             const AccumulationSettings& settings) {
  view_ = view;
  pixels_.assign(size_t(view.resolution.x) * size_t(view.resolution.y), PixelRay{});
  rows_.resize(size_t(view.resolution.y));
  for (std::vector<VolumeInterval>& row : rows_) row.clear();
  if (volumes.empty()) return;
  parallel_for(view.resolution.y, [&](int y) {
    thread_local VolumeContext scratch;
    std::vector<VolumeInterval>& row = rows_[size_t(y)];
    const float* d = depth.row(y);
    // The tile key changes every tile_size pixels: one hash per tile and row, not per pixel.
    const int tile = std::max(1, settings.tile_size);
    uint32_t key = 0;
    for (int x = 0; x < view.resolution.x; ++x) {
      if (x % tile == 0) key = interleave_tile_key(x, y, settings.tile_size, settings.frame_seed);
      PixelRay& p = pixels_[size_t(y) * size_t(view.resolution.x) + x];
      const Ray ray = view.ray({float(x) + 0.5f, float(y) + 0.5f});
      p.origin = ray.origin;
      p.dir = ray.direction;
      p.t_end = d[x] / view.depth_per_t(ray.direction);
      p.offset = interleaved_offset_keyed(x, y, settings.tile_size, key);
      p.first = uint32_t(row.size());
      if (!(p.t_end > 0.0f)) continue;
      // Every medium from the eye on: the camera's transmittance needs those before a
      // light's volume too.
      volumes.intervals(Ray{ray.origin, ray.direction, 0.0f, p.t_end}, scratch);
      float t0 = kInfinity, t1 = -kInfinity;
      for (const VolumeInterval& iv : scratch.intervals) {
        t0 = std::min(t0, iv.t0);
        t1 = std::max(t1, iv.t1);
        row.push_back(iv);
      }
      p.count = uint32_t(scratch.intervals.size());
      p.media_t0 = t0;
      p.media_t1 = t1;
    }
  });
}

}  // namespace caligo
