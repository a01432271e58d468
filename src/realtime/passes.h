// The real-time frame passes after the scene buffers, each a function from images to
// images (no hidden state), so they can be timed, tested and later moved to a GPU one by
// one. Every pass has a SIMD path (xsimd) and a scalar path; `simd = false` selects the
// scalar one, which the tests compare against.
#pragma once

#include <cstdint>
#include <span>

#include "realtime/frame_light.h"
#include "realtime/plane.h"
#include "realtime/view.h"
#include "settings/realtime_settings.h"

namespace caligo {

class VolumeScene;

// Low-resolution depth for accumulation, gather, temporal and upsample (low_depth.cpp): each
// pixel the full-resolution depth under its centre (its ray ends exactly where that
// full-resolution ray does), or with `min_max` the nearest or farthest depth of its block
// where the neighbouring centres leave that surface out (a thin cable, a slit), so every
// surface of a block reaches the upsample's taps. Depths agree within `relative_threshold`.
Plane downsample_depth(const Plane& full_depth, int scale, LowResolutionDepth mode = LowResolutionDepth::min_max,
                       float relative_threshold = 0.05f);

// Adds one light's single-scattered radiance along each pixel ray of `view` (the camera at
// accumulation resolution) to `accum`, marching only inside the light's volume, clamped to
// `depth` (linear, same resolution) and to the volume primitives.
void accumulate_light(const FrameLight& light, const VolumeScene& volumes, const View& view,
                      const Plane& depth, const AccumulationSettings& settings, ColorPlanes& accum);

// Separable (2 radius + 1)-tap Gaussian with depth weights exp(-falloff |d - d0 - k s| / d0),
// s the depth's slope at the centre along the pass (gather.cpp; 0 with follow_slope false,
// the seed's weight).
ColorPlanes bilateral_gather(const ColorPlanes& in, const Plane& depth, int radius, float depth_falloff,
                             bool simd = true, bool follow_slope = false);

// Full-resolution result from the low-resolution one: the bilinear blend of those of the four
// low-resolution taps around a pixel whose depth agrees with its own (all four away from
// edges), the tap of nearest depth where none does.
ColorPlanes upsample_nearest_depth(const ColorPlanes& low, const Plane& low_depth, const Plane& full_depth,
                                   float relative_threshold = 0.05f, bool simd = true);
// The same into a caller-owned buffer (resized if needed): a frame loop reuses it and
// saves a 25 MB allocation and its page faults at 1080p.
void upsample_nearest_depth(const ColorPlanes& low, const Plane& low_depth, const Plane& full_depth,
                            ColorPlanes& out, float relative_threshold = 0.05f, bool simd = true);

// History blend: each pixel is reprojected into the previous frame with the previous view;
// history is rejected where the previous depth there disagrees (disocclusion) and weighted
// down by luminance difference. blend = weight of the current frame (1 = no history).
ColorPlanes temporal_reproject(const ColorPlanes& current, const Plane& depth, const View& view,
                               const ColorPlanes& history, const Plane& history_depth,
                               const View& history_view, float blend, bool simd = true);
// The same into a caller-owned buffer (resized if needed; must not alias the inputs).
void temporal_reproject(const ColorPlanes& current, const Plane& depth, const View& view,
                        const ColorPlanes& history, const Plane& history_depth, const View& history_view,
                        float blend, ColorPlanes& out, bool simd = true);

}  // namespace caligo
