// The `cloud` built-in (a generated 128^3 VDB cumulus, albedo 0.99, 64 bounces):
//  - BM_CloudSkipping: shader evaluations per camera path (camera, bounce and shadow rays)
//    with empty-space skipping and constant blocks in one step, with only the former, and
//    with neither (the grid marched as one box, voxel by voxel);
//  - BM_CloudRender: the scene at a fixed resolution and spp;
//  - BM_CloudEfficiency: MSE against a high-spp reference for the production path tracer
//    and for the reference ladder's delta tracking, with time x MSE (the time to reach a
//    given MSE, up to a constant: MSE falls as 1/time for both) and their ratio.
#include <benchmark/benchmark.h>

#include "bench_reference.h"

#include <chrono>

#include "bench_scene.h"
#include "image/compare.h"
#include "integrators/reference.h"
#include "render/render.h"

namespace caligo {
namespace {

constexpr Vec2i kEfficiencyResolution{64, 36};

RenderSettings cloud_settings(Vec2i resolution, int spp, uint64_t seed) {
  RenderSettings s = render_settings(bench::builtin_scene("cloud").desc());
  s.resolution = resolution;
  s.spp = spp;
  s.seed = seed;
  return s;
}

void BM_CloudSkipping(benchmark::State& state) {
  const Scene& scene = bench::builtin_scene("cloud");
  RenderSettings s = cloud_settings({96, 54}, 4, 1);
  s.march.skip_empty_blocks = state.range(0) != 0;
  s.march.constant_blocks_one_step = state.range(1) != 0;
  RenderStats stats;
  for (auto _ : state) stats = render(scene, s).stats;
  state.counters["camera_evals/path"] = double(stats.camera_march_steps) / double(stats.paths);
  state.counters["shader_evals/path"] = double(stats.shader_evaluations) / double(stats.paths);
  state.counters["steps/path"] = double(stats.march_steps) / double(stats.paths);
}
BENCHMARK(BM_CloudSkipping)
    ->ArgNames({"skip_empty", "constant_one_step"})
    ->Args({1, 1})
    ->Args({1, 0})
    ->Args({0, 0})
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(1);

void BM_CloudRender(benchmark::State& state) {
  const Scene& scene = bench::builtin_scene("cloud");
  const RenderSettings s = cloud_settings({int(state.range(0)), int(state.range(0)) * 9 / 16}, int(state.range(1)), 1);
  uint64_t paths = 0;
  for (auto _ : state) paths += render(scene, s).stats.paths;
  state.counters["paths/s"] = benchmark::Counter(double(paths), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_CloudRender)->Args({160, 16})->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

// The reference both estimators are measured against: the production tracer at high spp
// (the test GridVolume.ProductionMarcherAgreesWithDeltaTrackingOnAGridCloud holds the two
// estimators' means within 1 % of each other on a grid cloud).
const Image& cloud_reference() {
  static const Image image = render(bench::builtin_scene("cloud"), cloud_settings(kEfficiencyResolution, 512, 999)).image;
  return image;
}

Image to_image(const std::vector<RGB>& pixels, Vec2i resolution) {
  Image image(resolution.x, resolution.y, {"R", "G", "B"});
  for (int y = 0; y < resolution.y; ++y)
    for (int x = 0; x < resolution.x; ++x) image.set_rgb(x, y, 0, pixels[size_t(y) * size_t(resolution.x) + size_t(x)]);
  return image;
}

void BM_CloudEfficiency(benchmark::State& state) {
  const bool delta_tracking = state.range(0) != 0;
  const int spp = int(state.range(1));
  const Scene& scene = bench::builtin_scene("cloud");
  const Image& reference = cloud_reference();
  double seconds = 0, mse = 0;
  int runs = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    Image image;
    if (delta_tracking) {
      ReferenceOptions o;
      o.samples_per_pixel = spp;
      o.limits = scene.desc().render.path.limits;
      o.seed = uint64_t(runs) + 1;
      image = to_image(reference_image(scene, kEfficiencyResolution, o), kEfficiencyResolution);
    } else {
      image = render(scene, cloud_settings(kEfficiencyResolution, spp, uint64_t(runs) + 1)).image;
    }
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    mse += bench::mse(image, reference);
    ++runs;
  }
  state.counters["MSE"] = mse / runs;
  state.counters["time_x_MSE"] = seconds / runs * mse / runs;
}
BENCHMARK(BM_CloudEfficiency)
    ->ArgNames({"delta_tracking", "spp"})
    ->Args({0, 16})
    ->Args({1, 16})
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(2);

}  // namespace
}  // namespace caligo
