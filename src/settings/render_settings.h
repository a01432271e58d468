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
};

}  // namespace caligo
