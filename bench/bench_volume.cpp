// Distance sampling for light in media on `lamp-in-fog`: density-only, equiangular-only and
// MIS at equal samples per pixel, for single scattering (bounces 1) and all orders (128), each measured
// against a high-spp MIS reference rendered once per process. Counters: MSE against the reference, and per
// camera ray the march steps of its own record and all march steps / shader evaluations (including shadow
// rays).
#include <benchmark/benchmark.h>

#include "bench_reference.h"

#include <map>

#include "bench_scene.h"
#include "image/compare.h"
#include "render/render.h"

namespace caligo {
namespace {

constexpr Vec2i kResolution{160, 120};
constexpr int kReferenceSpp = 1024;

RenderSettings lamp_settings(DistanceSampling sampling, int spp, uint64_t seed, int bounces) {
  RenderSettings s = render_settings(bench::builtin_scene("lamp-in-fog").desc());
  s.resolution = kResolution;
  s.spp = spp;
  s.seed = seed;
  s.path.distance_sampling = sampling;
  s.path.limits.max_volume_bounces = bounces;
  return s;
}

// References for single scattering (bounces = 1) and the scene's full multiple scattering.
const Image& reference(int bounces) {
  static std::map<int, Image> cache;
  auto it = cache.find(bounces);
  if (it == cache.end()) {
    const RenderSettings s = lamp_settings(DistanceSampling::kMis, kReferenceSpp, 12345, bounces);
    it = cache.emplace(bounces, render(bench::builtin_scene("lamp-in-fog"), s).image).first;
  }
  return it->second;
}

void BM_LampInFog(benchmark::State& state) {
  const auto sampling = DistanceSampling(state.range(0));
  const int spp = int(state.range(1));
  const int bounces = int(state.range(2));
  const Image& ref = reference(bounces);
  const Scene& scene = bench::builtin_scene("lamp-in-fog");
  double mse = 0.0;
  RenderStats stats;
  int runs = 0;
  for (auto _ : state) {
    const RenderResult r = render(scene, lamp_settings(sampling, spp, uint64_t(runs), bounces));
    mse += bench::mse(r.image, ref);
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
    ->ArgNames({"sampling", "spp", "bounces"})
    ->Args({int(DistanceSampling::kDensity), 16, 1})
    ->Args({int(DistanceSampling::kEquiangular), 16, 1})
    ->Args({int(DistanceSampling::kMis), 16, 1})
    ->Args({int(DistanceSampling::kDensity), 16, 128})
    ->Args({int(DistanceSampling::kEquiangular), 16, 128})
    ->Args({int(DistanceSampling::kMis), 16, 128})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(3);

}  // namespace
}  // namespace caligo
