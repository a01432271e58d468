// Distance sampling for light in media on `lamp-in-fog`: density-only, equiangular-only and
// MIS at equal samples per pixel, each measured against a high-spp MIS reference rendered
// once per process. Counters: MSE against the reference, and per camera ray the march steps
// of its own record and all march steps / shader evaluations (including shadow rays).
#include <benchmark/benchmark.h>

#include "bench_scene.h"
#include "image/compare.h"
#include "render/render.h"

namespace caligo {
namespace {

constexpr Vec2i kResolution{160, 120};
constexpr int kReferenceSpp = 1024;

RenderSettings lamp_settings(DistanceSampling sampling, int spp, uint64_t seed) {
  RenderSettings s = default_settings(bench::builtin_scene("lamp-in-fog").desc());
  s.resolution = kResolution;
  s.spp = spp;
  s.seed = seed;
  s.distance_sampling = sampling;
  return s;
}

const Image& reference() {
  static const Image image =
      render(bench::builtin_scene("lamp-in-fog"), lamp_settings(DistanceSampling::kMis, kReferenceSpp, 12345))
          .image;
  return image;
}

void BM_LampInFog(benchmark::State& state) {
  const auto sampling = DistanceSampling(state.range(0));
  const int spp = int(state.range(1));
  const Image& ref = reference();
  const Scene& scene = bench::builtin_scene("lamp-in-fog");
  double mse = 0.0;
  RenderStats stats;
  int runs = 0;
  for (auto _ : state) {
    const RenderResult r = render(scene, lamp_settings(sampling, spp, uint64_t(runs)));
    const double rmse = compare_images(r.image, ref).rmse;
    mse += rmse * rmse;
    stats = r.stats;
    ++runs;
  }
  const double camera_rays = double(stats.paths);
  state.counters["MSE"] = mse / runs;
  state.counters["record_steps/ray"] = double(stats.camera_march_steps) / camera_rays;
  state.counters["all_steps/ray"] = double(stats.march_steps) / camera_rays;
  state.counters["shader_evals/ray"] = double(stats.shader_evaluations) / camera_rays;
}
BENCHMARK(BM_LampInFog)
    ->ArgNames({"sampling", "spp"})
    ->Args({int(DistanceSampling::kDensity), 16})
    ->Args({int(DistanceSampling::kEquiangular), 16})
    ->Args({int(DistanceSampling::kMis), 16})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(3);

}  // namespace
}  // namespace caligo
