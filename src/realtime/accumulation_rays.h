// The camera side of the accumulation pass, shared by every light of a frame: each
// low-resolution pixel's ray, where it ends (the depth buffer), the volume primitives on
// it and its interleaved march offset. Finding those once per frame instead of once per
// light saves a BVH query and a permutation per pixel and light; a light then only clips
// the ray to its own volume. Built in parallel, read-only afterwards (thread-safe).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "realtime/passes.h"
#include "volumes/volume_scene.h"

namespace caligo {

class AccumulationRays {
 public:
  struct PixelRay {
    Vec3 origin, dir;       // dir unit
    float t_end = 0.0f;     // the depth buffer's surface (or the far end of the sky)
    float media_t0 = 0.0f;  // extent of the media on [0, t_end]; empty when t0 >= t1
    float media_t1 = 0.0f;
    float offset = 0.5f;            // interleaved_offset of the pixel
    uint32_t first = 0, count = 0;  // its intervals in the row's list
  };

  AccumulationRays() = default;
  // `depth` is linear depth at the resolution of `view`; settings give tile size and seed.
  AccumulationRays(const VolumeScene& volumes, const View& view, const Plane& depth,
                   const AccumulationSettings& settings) {
    build(volumes, view, depth, settings);
  }
  // Rebuilds for a new frame, reusing the buffers (a frame loop keeps one instance: its
  // 6 MB at 480x270 would otherwise be page-faulted in afresh every frame).
  void build(const VolumeScene& volumes, const View& view, const Plane& depth,
             const AccumulationSettings& settings);

  const View& view() const { return view_; }
  const PixelRay& pixel(int x, int y) const { return pixels_[size_t(y) * size_t(view_.resolution.x) + x]; }
  // The volume primitives the pixel's ray crosses before t_end, in no particular order.
  std::span<const VolumeInterval> intervals(int y, const PixelRay& ray) const {
    return std::span<const VolumeInterval>(rows_[size_t(y)]).subspan(ray.first, ray.count);
  }

 private:
  View view_;
  std::vector<PixelRay> pixels_;
  std::vector<std::vector<VolumeInterval>> rows_;  // one list per image row (built in parallel)
};

// accumulate_light over precomputed rays: the same result as passes.h's accumulate_light
// with rays.view(), the depth and the settings the rays were built with.
void accumulate_light(const FrameLight& light, const VolumeScene& volumes, const AccumulationRays& rays,
                      const AccumulationSettings& settings, ColorPlanes& accum);

}  // namespace caligo
