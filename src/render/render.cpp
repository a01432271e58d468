#include "render/render.h"

#include <atomic>
#include <chrono>
#include <memory>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>

#include "core/parallel.h"
#include "core/sampler.h"
#include "render/film.h"

namespace caligo {

RenderSettings default_settings(const SceneDesc& desc) {
  RenderSettings s;
  s.resolution = desc.camera.resolution;
  s.spp = desc.render.spp;
  s.max_depth = desc.render.max_depth;
  s.max_volume_bounces = desc.render.max_volume_bounces;
  s.seed = desc.render.seed;
  return s;
}

namespace {

// One tile: every pixel, every sample, in a fixed order.
PathCounters render_tile(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                         const Tile& tile, Film& film, PathScratch& scratch) {
  PathSettings path_settings;
  path_settings.max_depth = settings.max_depth;
  path_settings.max_volume_bounces = settings.max_volume_bounces;
  path_settings.distance_sampling = settings.distance_sampling;
  path_settings.absorption_by_weight = settings.absorption_by_weight;
  path_settings.deferred_nee = settings.deferred_nee;
  path_settings.light_sampler = settings.light_sampler;
  scratch.march_settings = settings.march;
  PathCounters counters;
  for (int y = tile.y0; y < tile.y1; ++y)
    for (int x = tile.x0; x < tile.x1; ++x)
      for (int s = 0; s < settings.spp; ++s) {
        const Sampler sampler(settings.seed, {x, y}, uint32_t(s));
        const Vec2 jitter = sampler.get_2d(sample_dim::kFilm);
        const Ray ray = camera.generate_ray({float(x) + jitter.x, float(y) + jitter.y});
        const PathSample sample = trace_path(scene, ray, sampler, path_settings, counters, scratch);
        film.add(x, y, sample, sample.alpha > 0.0f ? camera.depth(ray, sample.hit_t) : kInfinity);
      }
  return counters;
}

}  // namespace

RenderResult render(const Scene& scene, const RenderSettings& settings, Progress::Style progress_style) {
  std::unique_ptr<tbb::global_control> thread_limit;
  if (settings.threads > 0)
    thread_limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                         size_t(settings.threads));
  const Camera camera = scene.camera(settings.resolution);
  Film film(settings.resolution);
  const auto tiles = make_tiles(settings.resolution, settings.tile_size);
  const uint64_t paths =
      uint64_t(settings.resolution.x) * uint64_t(settings.resolution.y) * uint64_t(settings.spp);
  std::atomic<uint64_t> rays{0}, march_steps{0};
  tbb::enumerable_thread_specific<PathScratch> scratch;  // per-thread march buffers and record

  const auto start = std::chrono::steady_clock::now();
  {
    Progress progress("render", paths, progress_style);
    parallel_for_tiles(tiles, [&](const Tile& tile) {
      const PathCounters c = render_tile(scene, camera, settings, tile, film, scratch.local());
      rays.fetch_add(c.rays, std::memory_order_relaxed);
      march_steps.fetch_add(c.camera_march_steps, std::memory_order_relaxed);
      progress.advance(uint64_t(tile.x1 - tile.x0) * uint64_t(tile.y1 - tile.y0) * uint64_t(settings.spp));
    });
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  RenderStats stats{seconds, paths, rays.load(), march_steps.load()};
  for (const PathScratch& s : scratch) {
    stats.march_steps += s.march.steps;
    stats.shader_evaluations += s.march.shader_evaluations;
  }
  return {film.resolve(settings.spp), stats};
}

}  // namespace caligo
