#include "render/render.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>

#include "core/parallel.h"
#include "core/sampler.h"
#include "integrators/path_tracer.h"
#include "render/film.h"
#include "render/pixel_filter.h"
#include "guiding/guiding_schedule.h"

namespace caligo {

RenderSettings render_settings(const SceneDesc& desc) {
  RenderSettings s = desc.render;
  s.resolution = desc.camera.resolution;
  return s;
}

namespace {

// The tiles of the crop window: make_tiles over its size, moved to its corner.
std::vector<Tile> crop_tiles(const PixelBounds& bounds, int tile_size) {
  std::vector<Tile> tiles = make_tiles({bounds.width(), bounds.height()}, tile_size);
  for (Tile& t : tiles) {
    t.x0 += bounds.min.x;
    t.x1 += bounds.min.x;
    t.y0 += bounds.min.y;
    t.y1 += bounds.min.y;
  }
  return tiles;
}

// The samples a pass adds to one pixel: [first, last).
struct SampleSpan {
  int first, last;
};

// Adaptive sampling's stopping rule (RenderSettings::adaptive) for a pixel about to take sample s.
struct AdaptiveRule {
  double threshold = 0.0;
  int min_samples = 0, step = 1;
  explicit AdaptiveRule(const RenderSettings& settings) : threshold(settings.adaptive.threshold) {
    min_samples = settings.adaptive.min_samples > 0
                      ? settings.adaptive.min_samples
                      : std::max(16, int(std::lround(std::sqrt(double(std::max(0, settings.spp))))));
    step = std::max(1, min_samples / 2);
  }
  bool stops(const Film& film, int x, int y, int s) const {
    // Only a film that holds exactly the pixel's samples before s can judge it (not one rank's
    // part of a samples split over MPI, which the render command refuses with adaptive sampling).
    return threshold > 0.0 && s >= min_samples && (s - min_samples) % step == 0 &&
           film.sample_count(x, y) == uint32_t(s) && film.relative_error(x, y) < threshold;
  }
};

// SampleClamp: the direct and the indirect layers each scaled so that no channel of their sum
// exceeds the limit (the layers keep adding up to the beauty).
void clamp_sample(PathSample& sample, const SampleClamp& clamp) {
  const auto limit = [&](std::initializer_list<LightKind> kinds, float most) {
    if (!(most > 0.0f)) return;
    RGB sum;
    for (LightKind k : kinds) sum += sample.light[size_t(k)];
    const float peak = sum.max_component();
    if (!(peak > most)) return;
    for (LightKind k : kinds) sample.light[size_t(k)] *= most / peak;
  };
  limit({LightKind::kSurfaceDirect, LightKind::kVolumeDirect, LightKind::kSurfaceEmission, LightKind::kVolumeEmission,
         LightKind::kBackground},
        clamp.direct);
  limit({LightKind::kSurfaceIndirect, LightKind::kVolumeIndirect}, clamp.indirect);
}

// One tile: every pixel, its span's samples in index order. Stops between pixels once `stop`
// is set, so every pixel holds a prefix of its samples; returns the paths traced.
template <typename SpanOf>
PathCounters render_tile(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                         const PixelFilter& filter, const Tile& tile, Film& film, PathScratch& scratch,
                         const SpanOf& span_of, const std::atomic<bool>* stop, PathGuiding guiding, uint64_t& paths) {
  scratch.march_settings = settings.march;
  PathCounters counters;
  const bool lens = camera.has_aperture();
  const AdaptiveRule adaptive(settings);
  for (int y = tile.y0; y < tile.y1; ++y)
    for (int x = tile.x0; x < tile.x1; ++x) {
      if (stop && stop->load(std::memory_order_relaxed)) return counters;
      const SampleSpan span = span_of(x, y);
      int s = span.first;
      for (; s < span.last; ++s) {
        if (adaptive.stops(film, x, y, s)) break;
        const Sampler sampler(settings.seed, {x, y}, uint32_t(s));
        // Filter importance sampling: the sample lands where the pixel's filter puts it and
        // counts with weight 1 for this pixel only (render/pixel_filter.h).
        const Vec2 offset = filter.sample_offset(sampler.get_2d(sample_dim::kFilm));
        const Vec2 lens_u = lens ? sampler.get_2d(sample_dim::kLens) : Vec2{0.5f, 0.5f};
        const Ray ray = camera.generate_ray({float(x) + 0.5f + offset.x, float(y) + 0.5f + offset.y}, lens_u);
        PathSample sample = trace_path(scene, ray, sampler, settings.path, counters, scratch, guiding);
        if (settings.clamp.any()) clamp_sample(sample, settings.clamp);
        film.add(x, y, sample, sample.hit_t < kInfinity ? camera.depth(ray, sample.hit_t) : kInfinity);
      }
      paths += uint64_t(std::max(0, s - span.first));
    }
  return counters;
}

// The tile loop over the crop window shared by render_into and render_up_to.
template <typename SpanOf>
RenderStats run_pass(Film& film, const Scene& scene, const RenderSettings& settings, uint64_t total_paths,
                     const SpanOf& span_of, const std::atomic<bool>* stop, Progress::Style progress_style,
                     PathGuiding guiding = {}, const std::string& label = "render", Progress* shared = nullptr) {
  if (film.resolution() != settings.resolution || film.aovs() != settings.aovs)
    throw std::invalid_argument("render: the film does not match the settings' resolution and outputs");
  std::unique_ptr<tbb::global_control> thread_limit;
  if (settings.threads > 0)
    thread_limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                         size_t(settings.threads));
  const Camera camera = scene.camera(settings.resolution);
  const PixelFilter filter(settings.filter);
  const PixelBounds bounds = settings.crop.pixels(settings.resolution);
  const auto tiles = bounds.empty() ? std::vector<Tile>{} : crop_tiles(bounds, settings.tile_size);
  std::atomic<uint64_t> rays{0}, march_steps{0}, paths{0};
  tbb::enumerable_thread_specific<PathScratch> scratch;  // per-thread march buffers and record

  const auto start = std::chrono::steady_clock::now();
  {
    std::optional<Progress> own;  // a pass of its own, or one of a progressive render's (`shared`)
    if (!shared) own.emplace(label, total_paths, progress_style);
    Progress& progress = shared ? *shared : *own;
    parallel_for_tiles(tiles, [&](const Tile& tile) {
      uint64_t tile_paths = 0;
      const PathCounters c =
          render_tile(scene, camera, settings, filter, tile, film, scratch.local(), span_of, stop, guiding, tile_paths);
      rays.fetch_add(c.rays, std::memory_order_relaxed);
      march_steps.fetch_add(c.camera_march_steps, std::memory_order_relaxed);
      paths.fetch_add(tile_paths, std::memory_order_relaxed);
      progress.advance(tile_paths);
    });
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  RenderStats stats{seconds, paths.load(), rays.load(), march_steps.load()};
  for (const PathScratch& s : scratch) {
    stats.march_steps += s.march.steps;
    stats.shader_evaluations += s.march.shader_evaluations;
  }
  return stats;
}

uint64_t crop_pixels(const RenderSettings& settings) {
  const PixelBounds b = settings.crop.pixels(settings.resolution);
  return b.empty() ? 0 : uint64_t(b.width()) * uint64_t(b.height());
}

}  // namespace

RenderStats render_into(Film& film, const Scene& scene, const RenderSettings& settings,
                        Progress::Style progress_style, PathGuiding guiding) {
  if (settings.spp < 0 || settings.first_sample < 0) throw std::invalid_argument("render_into: negative sample range");
  const SampleSpan span{settings.first_sample, settings.first_sample + settings.spp};
  return run_pass(film, scene, settings, crop_pixels(settings) * uint64_t(settings.spp),
                  [span](int, int) { return span; }, nullptr, progress_style, guiding);
}

namespace {

// Every pixel of the crop window from its own count up to `target`, in one pass.
RenderStats pass_up_to(Film& film, const Scene& scene, const RenderSettings& settings, int target,
                       const std::atomic<bool>* stop, Progress::Style progress_style, PathGuiding guiding = {},
                       const std::string& label = "render", Progress* shared = nullptr) {
  uint64_t remaining = 0;
  const PixelBounds b = settings.crop.pixels(settings.resolution);
  for (int y = b.min.y; y < b.max.y; ++y)
    for (int x = b.min.x; x < b.max.x; ++x) remaining += uint64_t(std::max(0, target - int(film.sample_count(x, y))));
  // A film of first_sample k holds samples k, k + 1, ...: its counts start at 0 all the same.
  const int offset = settings.first_sample;
  return run_pass(
      film, scene, settings, remaining,
      [&film, target, offset](int x, int y) { return SampleSpan{offset + int(film.sample_count(x, y)), offset + target}; },
      stop, progress_style, guiding, label, shared);
}

bool stopped(const std::atomic<bool>* stop) { return stop && stop->load(std::memory_order_relaxed); }

}  // namespace

GuidingConfig guiding_config(const RenderSettings& settings) {
  // Mueller et al.'s c = 12000 vertices per leaf was set for megapixel images; smaller ones would
  // get a handful of leaves (a point light seen from everywhere at once), so c follows the crop
  // window's pixels below 2^20, down to 1/16 of it.
  GuidingConfig config;
  const PixelBounds b = settings.crop.pixels(settings.resolution);
  const double pixels = b.empty() ? 0.0 : double(b.width()) * double(b.height());
  config.spatial_threshold *= std::clamp(pixels / double(1 << 20), 1.0 / 16.0, 1.0);
  return config;
}

bool guided(const RenderSettings& settings) {
  return settings.path.guiding != GuidingMode::kOff && settings.path.deferred_nee <= 0;
}

Bounds3 guiding_bounds(const Scene& scene) {
  Bounds3 b = scene.surfaces().bounds();
  for (const VolumePrimitive& p : scene.volumes().primitives()) {
    const Bounds3 v = volume_bounds(p.shape);
    if (is_finite(v.lo) && is_finite(v.hi) && !v.empty()) b.extend(v);
  }
  if (!is_finite(b.lo) || !is_finite(b.hi)) return {};
  return b;
}

GuidingField guiding_field_of(const Film& film, const Scene& scene, const RenderSettings& settings) {
  if (film.training_state().empty()) return GuidingField(guiding_bounds(scene), guiding_config(settings));
  return GuidingField::from_bytes(film.training_state(), "the film's guiding field");
}

RenderStats render_up_to(Film& film, const Scene& scene, const RenderSettings& settings, int target,
                         const std::atomic<bool>* stop, Progress::Style progress_style, Progress* shared_progress) {
  if (target < 0) throw std::invalid_argument("render_up_to: negative sample count");
  if (!guided(settings)) return pass_up_to(film, scene, settings, target, stop, progress_style, {}, "render", shared_progress);
  // Path guiding: one pass per training iteration (guiding/guiding_schedule.h), the field refined
  // between them; the field goes back into the film, so a checkpoint holds it.
  const auto start = std::chrono::steady_clock::now();
  GuidingField field = guiding_field_of(film, scene, settings);
  RenderStats stats;
  for (;;) {
    const int iteration = field.completed_iterations();
    const bool train = field.training();
    const int end = train ? std::min(target, training_iteration_end(iteration)) : target;
    const std::string label = train ? "render (guiding: training " + std::to_string(iteration + 1) + "/" +
                                          std::to_string(field.config().iterations) + ")"
                                    : "render";
    stats += pass_up_to(film, scene, settings, end, stop, progress_style, {&field, train}, label, shared_progress);
    if (!train || stopped(stop) || end < training_iteration_end(iteration)) break;
    field.finish_iteration();
    if (end >= target) break;
  }
  film.set_training_state(field.to_bytes());
  stats.guiding = {field.completed_iterations(), field.spatial_leaves(), field.directional_nodes(),
                   field.memory_bytes()};
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

RenderResult render(const Scene& scene, const RenderSettings& settings, Progress::Style progress_style) {
  Film film(settings.resolution, settings.aovs);
  if (guided(settings)) {
    if (settings.spp < 0 || settings.first_sample != 0)
      throw std::invalid_argument("render: a guided render starts at sample 0");
    const RenderStats stats = render_up_to(film, scene, settings, settings.spp, nullptr, progress_style);
    return {film.resolve(), stats};
  }
  const RenderStats stats = render_into(film, scene, settings, progress_style);
  return {film.resolve(), stats};
}

}  // namespace caligo
