// Everything that says how the path tracer renders (as opposed to what): plain data, passed by
// value, never global. A scene file's "render" object fills one (SceneDesc::render) and the
// render command's options override it.
#pragma once

#include <cstdint>

#include "core/crop_window.h"
#include "core/vec.h"
#include "settings/aov.h"
#include "settings/march_settings.h"
#include "settings/path_settings.h"
#include "settings/pixel_filter_desc.h"

namespace caligo {

// Adaptive sampling (render/render.cpp): a pixel stops taking samples once its estimated relative
// error (Film::relative_error, from its own samples alone) is below `threshold`, tested when its
// count reaches min_samples and every min_samples / 2 samples after. Pixel by pixel and at fixed
// counts, so the image does not depend on threads, passes, checkpoints or a rows split over MPI
// ranks. Opt-in: a pixel whose few samples happen to agree stops early, a small bias towards
// what those samples saw (docs/noise.md).
struct AdaptiveSampling {
  float threshold = 0.0f;  // 0: off (every pixel takes every sample)
  int min_samples = 0;     // 0: automatic, max(16, sqrt(spp))
  friend bool operator==(const AdaptiveSampling&, const AdaptiveSampling&) = default;
};

// Clamping of sample values (Cycles' Clamp Direct / Indirect, Arnold's AA_sample_clamp): the light
// a sample brings with at most one diffuse event (direct light, emission and background seen) and
// the rest (indirect), each scaled down so that no channel exceeds its limit. Biased (energy is
// lost), so off by default: it trades fireflies for a darker, wrong image.
struct SampleClamp {
  float direct = 0.0f;    // 0: no limit
  float indirect = 0.0f;  // 0: no limit
  bool any() const { return direct > 0.0f || indirect > 0.0f; }
  friend bool operator==(const SampleClamp&, const SampleClamp&) = default;
};

struct RenderSettings {
  Vec2i resolution{640, 480};
  int spp = 16;
  PathSettings path;  // passed to trace_path as it is; the scene file sets its limits and priority_shadows
  uint64_t seed = 0;
  int threads = 0;  // 0: all hardware threads
  int tile_size = 16;
  MarchSettings march;  // step rules of the decoupled ray marcher
  // Where each sample lands in its pixel: render/pixel_filter.h builds the filter from this and
  // shows the loop (the kFilm sample, weight 1). Default: box of radius 0.5, the uniform jitter.
  PixelFilterDesc filter;
  // The pixels rendered: crop.pixels(resolution); the image keeps the full resolution.
  CropWindow crop;
  // The outputs the film holds and the image gets (settings/aov.h; --aov).
  AovSet aovs = AovSet::defaults();
  // The samples of each pixel this render adds: [first_sample, first_sample + spp). A frame
  // split into sample ranges (checkpoints, processes) and merged equals one render of them all.
  int first_sample = 0;
  AdaptiveSampling adaptive;
  SampleClamp clamp;
};

}  // namespace caligo
