#include "render/progressive.h"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>
#include <thread>

namespace caligo {
namespace {

struct Clock {
  std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
};

bool stopped(const std::atomic<bool>* stop) { return stop && stop->load(std::memory_order_relaxed); }

// The stop a pass sees: the caller's, or the time limit reached. The scheduler sizes passes to
// end before the limit, but on a busy machine a pass can take far longer than the last one
// did; a thread watching the clock then cuts it at the limit (pixels keep what they hold).
class DeadlineWatch {
 public:
  DeadlineWatch(const Clock& clock, std::optional<double> limit, const std::atomic<bool>* outer) : outer_(outer) {
    if (!limit) return;
    watcher_ = std::thread([this, &clock, limit] {
      std::unique_lock lock(mutex_);
      while (!done_) {
        if (stopped(outer_) || clock.seconds() >= *limit) {
          cut_ = !stopped(outer_);
          flag_.store(true, std::memory_order_relaxed);
          return;
        }
        wake_.wait_for(lock, std::chrono::milliseconds(5));
      }
    });
  }
  ~DeadlineWatch() {
    if (!watcher_.joinable()) return;
    {
      std::lock_guard lock(mutex_);
      done_ = true;
    }
    wake_.notify_all();
    watcher_.join();
  }
  const std::atomic<bool>* flag() const { return watcher_.joinable() ? &flag_ : outer_; }
  // Whether the limit (not the caller) stopped the pass.
  bool cut() const {
    std::lock_guard lock(mutex_);
    return cut_;
  }

 private:
  const std::atomic<bool>* outer_;
  std::atomic<bool> flag_{false};
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  bool done_ = false, cut_ = false;
  std::thread watcher_;
};

// The next pass's sample count from `done`: doubling, bounded by the checkpoint interval and
// by what fits before the time limit (0: nothing fits).
int next_batch(const ProgressiveSchedule& schedule, int done, double seconds_per_sample, double elapsed) {
  if (done == 0 || seconds_per_sample <= 0.0) return 1;
  // In double until the end: a long limit over a fast pass overflows an int (the former
  // scheduler stopped such renders after their first sample).
  double batch = std::max(1, done);
  if (schedule.checkpoint_every) batch = std::min(batch, std::max(1.0, *schedule.checkpoint_every / seconds_per_sample));
  if (schedule.time_limit) batch = std::min(batch, (*schedule.time_limit - elapsed) / seconds_per_sample);
  return batch < 1.0 ? 0 : int(batch);
}

// Why the passes end after this one, or empty when they go on.
std::string stop_reason(const ProgressiveSchedule& schedule, const Film& film, double elapsed) {
  if (schedule.target_rmse) {
    const auto rmse = film.estimated_rmse();
    if (rmse && *rmse <= *schedule.target_rmse) return "the target RMSE (estimated " + std::to_string(*rmse) + ")";
  }
  if (schedule.time_limit && elapsed >= *schedule.time_limit) return "the time limit";
  return {};
}

void checkpoint(const ProgressiveHooks& hooks, const Film& film) {
  if (!hooks.save_checkpoint) return;
  try {
    hooks.save_checkpoint(film);
  } catch (const std::exception& e) {
    if (hooks.on_checkpoint_failed) hooks.on_checkpoint_failed(e);
  }
}

}  // namespace

ProgressiveResult render_progressive(Film& film, const Scene& scene, const RenderSettings& settings,
                                     const ProgressiveSchedule& schedule, const ProgressiveHooks& hooks,
                                     const std::atomic<bool>* stop, Progress::Style progress) {
  const Clock clock;
  const int target = settings.spp;
  ProgressiveResult result;
  if (!schedule.passes()) {
    result.stats = render_up_to(film, scene, settings, target, stop, progress);
    result.stats.seconds = clock.seconds();
    return result;
  }
  double last_checkpoint = 0.0, seconds_per_sample = 0.0;
  const DeadlineWatch watch(clock, schedule.time_limit, stop);
  // One progress line over every pass: the samples the crop window still needs.
  uint64_t remaining = 0;
  const PixelBounds bounds = settings.crop.pixels(settings.resolution);
  for (int y = bounds.min.y; y < bounds.max.y; ++y)
    for (int x = bounds.min.x; x < bounds.max.x; ++x) remaining += uint64_t(std::max(0, target - int(film.sample_count(x, y))));
  Progress shared("render", remaining, progress);
  for (int done = sample_range(film, settings).first; done < target && !stopped(stop);) {
    const int batch = next_batch(schedule, done, seconds_per_sample, clock.seconds());
    if (batch < 1) {
      result.stopped_by = "the time limit";
      break;
    }
    const int next = std::min(target, done + batch);
    const RenderStats pass = render_up_to(film, scene, settings, next, watch.flag(), Progress::Style::kQuiet, &shared);
    result.stats += pass;
    if (stopped(stop)) break;
    if (watch.cut()) {
      result.stopped_by = "the time limit, which cut the last pass (pixels hold their own sample counts)";
      break;
    }
    seconds_per_sample = pass.seconds / double(next - done);
    done = next;
    if (hooks.on_pass) hooks.on_pass(done, target, clock.seconds());
    result.stopped_by = stop_reason(schedule, film, clock.seconds());
    if (!result.stopped_by.empty()) break;
    if (schedule.checkpoint_every && done < target && clock.seconds() - last_checkpoint >= *schedule.checkpoint_every) {
      checkpoint(hooks, film);
      last_checkpoint = clock.seconds();
    }
  }
  result.stats.seconds = clock.seconds();
  return result;
}

std::pair<int, int> sample_range(const Film& film, const RenderSettings& settings) {
  const PixelBounds b = settings.crop.pixels(settings.resolution);
  uint32_t fewest = UINT32_MAX, most = 0;
  for (int y = b.min.y; y < b.max.y; ++y)
    for (int x = b.min.x; x < b.max.x; ++x) {
      fewest = std::min(fewest, film.sample_count(x, y));
      most = std::max(most, film.sample_count(x, y));
    }
  return b.empty() ? std::pair{0, 0} : std::pair{int(fewest), int(most)};
}

}  // namespace caligo
