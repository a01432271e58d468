// Whole renders of built-in scenes. BM_RenderDefault is the foundation target:
// default scene, 640x480, 64 spp (run with --benchmark_filter=Default/640).
#include <benchmark/benchmark.h>

#include "bench_scene.h"
#include "render/render.h"

namespace caligo {
namespace {

void BM_RenderDefault(benchmark::State& state) {
  const Scene& scene = bench::builtin_scene("default");
  RenderSettings settings = render_settings(scene.desc());
  settings.resolution = {int(state.range(0)), int(state.range(0)) * 3 / 4};
  settings.spp = int(state.range(1));
  uint64_t paths = 0, rays = 0;
  for (auto _ : state) {
    const RenderResult r = render(scene, settings);
    paths += r.stats.paths;
    rays += r.stats.rays;
  }
  state.counters["paths/s"] = benchmark::Counter(double(paths), benchmark::Counter::kIsRate);
  state.counters["rays/s"] = benchmark::Counter(double(rays), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_RenderDefault)
    ->Args({160, 16})
    ->Args({640, 64})
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(1);

}  // namespace
}  // namespace caligo
