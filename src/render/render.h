// Renders a Scene with the path tracer into an Image with AOVs: the tile loop, the film,
// sample generation and the statistics of the summary line.
#pragma once

#include <atomic>

#include "guiding/guiding_field.h"
#include "image/image.h"
#include "integrators/path_tracer.h"
#include "render/film.h"
#include "render/progress.h"
#include "settings/render_settings.h"
#include "scene/scene.h"

namespace caligo {

struct RenderStats {
  double seconds = 0.0;
  uint64_t paths = 0;
  uint64_t rays = 0;
  uint64_t camera_march_steps = 0;  // TransmittanceRecord steps of camera rays (per camera ray: / paths)
  uint64_t march_steps = 0;         // every marched step: camera, bounce and shadow rays
  uint64_t shader_evaluations = 0;  // every volume shader call
  // Path guiding's field after the render (all zero when it did not guide).
  struct Guiding {
    int iterations = 0;  // completed training iterations
    uint64_t leaves = 0, nodes = 0, bytes = 0;
  } guiding;

  // Adds another render's counts (passes, resumed work); `seconds` is left to the caller, who
  // times the whole. The guiding field's figures are the later render's.
  RenderStats& operator+=(const RenderStats& o) {
    if (o.guiding.leaves > 0) guiding = o.guiding;
    paths += o.paths;
    rays += o.rays;
    camera_march_steps += o.camera_march_steps;
    march_steps += o.march_steps;
    shader_evaluations += o.shader_evaluations;
    return *this;
  }
};

struct RenderResult {
  Image image;
  RenderStats stats;
};

// A fresh film of settings.resolution and settings.aovs, rendered and resolved.
RenderResult render(const Scene& scene, const RenderSettings& settings,
                    Progress::Style progress = Progress::Style::kQuiet);

// Adds samples [first_sample, first_sample + spp) of every pixel in the crop window to `film`
// (whose resolution and outputs must be settings'). Deterministic: the film ends the same bit
// for bit for any thread count, tile order or split of the sample range.
// A guided render (settings.path.guiding) needs the field the samples before first_sample left:
// `guiding` gives it (the MPI frame does, distributed/), and whether these samples train it.
RenderStats render_into(Film& film, const Scene& scene, const RenderSettings& settings,
                        Progress::Style progress = Progress::Style::kQuiet, PathGuiding guiding = {});

// Progressive and resumed rendering: brings every pixel of the crop window from its own sample
// count in `film` up to `target` samples (settings.spp is not used; settings.first_sample k makes
// the film hold samples k, k + 1, ..., k + target - 1, as the second half of `render --denoise`). When
// `stop` becomes true (a signal), the pass ends between pixels: every pixel then holds a prefix
// of its samples, so a later call continues it and ends bit for bit where one uninterrupted
// call would have.
// `shared_progress`, when given, reports these samples instead of a progress line of their own
// (a progressive render's passes share one).
RenderStats render_up_to(Film& film, const Scene& scene, const RenderSettings& settings, int target,
                         const std::atomic<bool>* stop = nullptr,
                         Progress::Style progress = Progress::Style::kQuiet, Progress* shared_progress = nullptr);

// Path guiding: whether these settings guide (settings.path.guiding, not with deferred NEE),
// the bounds its field covers, and the field a film holds (a fresh one when it holds none).
// render_up_to trains the field in the film's training state, iteration by iteration.
bool guided(const RenderSettings& settings);
Bounds3 guiding_bounds(const Scene& scene);
GuidingConfig guiding_config(const RenderSettings& settings);
GuidingField guiding_field_of(const Film& film, const Scene& scene, const RenderSettings& settings);

// The scene file's render settings at the camera's resolution.
RenderSettings render_settings(const SceneDesc& desc);

}  // namespace caligo
