// Progressive rendering of one frame in one process: passes of whole sample counts up to the
// target, with checkpoints between them, until the target, a time limit, an error target or a
// stop request. The render command drives it; it knows nothing of files or command lines (a
// checkpoint is a callback), so it is tested on its own (progressive_test.cpp).
#pragma once

#include <atomic>
#include <functional>
#include <optional>
#include <string>
#include <utility>

#include "render/render.h"

namespace caligo {

struct ProgressiveSchedule {
  std::optional<double> checkpoint_every;  // seconds between checkpoints
  std::optional<double> time_limit;        // seconds
  std::optional<double> target_rmse;       // the film's estimated RMSE (needs the variance AOV)
  // Refine the whole frame in passes of doubling sample counts even without any of the above,
  // so that a render stopped at any moment is a whole picture (caligo render's default).
  bool refine = false;
  // Without any of them the frame is one pass.
  bool passes() const { return refine || checkpoint_every || time_limit || target_rmse; }
};

struct ProgressiveHooks {
  // After each pass: samples per pixel done, the target, seconds since the start.
  std::function<void(int done, int target, double seconds)> on_pass;
  // At checkpoint times (not after the last pass): save the film. An exception it throws is
  // reported by on_checkpoint_failed and the render goes on (the film is still in memory).
  std::function<void(const Film&)> save_checkpoint;
  std::function<void(const std::exception&)> on_checkpoint_failed;
};

struct ProgressiveResult {
  RenderStats stats;       // seconds: the whole render
  std::string stopped_by;  // "the time limit", "the target RMSE (...)"; empty: target or stop
};

// Brings `film` (which may hold samples already: a resumed checkpoint) to settings.spp samples
// per pixel of the crop window, in passes when the schedule asks for them: 1 sample first,
// then as many as the last pass's time per sample says fit before the next checkpoint or the
// time limit (never more than doubling). `stop` ends the current pass between pixels, and so
// does the time limit when a pass runs past it (a busy machine): the limit is a deadline, and
// the pixels then hold their own counts. Otherwise the film ends bit for bit as one
// render_up_to to the same count would leave it.
ProgressiveResult render_progressive(Film& film, const Scene& scene, const RenderSettings& settings,
                                     const ProgressiveSchedule& schedule, const ProgressiveHooks& hooks,
                                     const std::atomic<bool>* stop = nullptr,
                                     Progress::Style progress = Progress::Style::kQuiet);

// The fewest and the most samples any pixel of settings' crop window has in `film`.
std::pair<int, int> sample_range(const Film& film, const RenderSettings& settings);

}  // namespace caligo
