// The integrator's defaults against the former ones at EQUAL TIME (issue 10): the light tree,
// solid-angle sampling of quads and triangles, equiangular sampling clipped to where the light
// reaches, absorption by weight and the optical-depth share of equiangular sampling, against
// power selection, area sampling, unclipped equiangular, analog free flight and the fixed 3/4
// share. Each scene's converged reference (new defaults, kReferenceSpp) is cached in the build
// folder (bench/defaults_reference_NAME_96x72_SPP.exr; delete it after changing the scene or
// the integrator). Counters: MSE and seconds of each, and mse_ratio = MSE(former) / MSE(new) at
// equal time, from MSE x seconds (the MSE of an unbiased estimator falls as 1 / time).
// Run: build/release/bench/caligo_bench --benchmark_filter=DefaultsEqualTime
#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>

#include "bench_reference.h"
#include "bench_scene.h"
#include "image/compare.h"
#include "image/exr_io.h"
#include "lights/area_light_sampling.h"
#include "render/render.h"

namespace caligo {
namespace {

constexpr Vec2i kResolution{96, 72};
constexpr int kReferenceSpp = 4096;
constexpr int kNewSpp = 32;
constexpr int kRuns = 4;

const char* const kScenes[] = {"lamp-in-fog", "default", "spot-shafts", "stage"};

RenderSettings settings(const char* scene, bool former, int spp, uint64_t seed) {
  RenderSettings s = render_settings(bench::builtin_scene(scene).desc());
  s.resolution = kResolution;
  s.spp = spp;
  s.seed = seed;
  if (former) {
    s.path.light_sampler = LightSamplerKind::kPower;
    s.path.absorption_by_weight = false;
    s.path.distance_sampling = DistanceSampling::kMisFixed;
  }
  return s;
}

RenderResult render_with(const char* scene, bool former, int spp, uint64_t seed) {
  set_light_sampling_options({!former, !former});
  RenderResult r = render(bench::builtin_scene(scene), settings(scene, former, spp, seed));
  set_light_sampling_options({});
  return r;
}

Image reference(const char* scene) {
  return bench::cached_reference(std::string("defaults_reference_") + scene, kResolution, kReferenceSpp,
                                 [&] { return render_with(scene, false, kReferenceSpp, 777).image; });
}

void BM_DefaultsEqualTime(benchmark::State& state) {
  const char* scene = kScenes[state.range(0)];
  const Image ref = reference(scene);
  const double new_rate = render_with(scene, false, 4, 99).stats.seconds / 4.0;
  const double old_rate = render_with(scene, true, 4, 99).stats.seconds / 4.0;
  const int old_spp = std::max(1, int(std::lround(kNewSpp * new_rate / old_rate)));
  double mse[2] = {0, 0}, seconds[2] = {0, 0}, paths[2] = {0, 0};
  for (auto _ : state)
    for (int run = 0; run < kRuns; ++run)
      for (int former = 0; former < 2; ++former) {
        const RenderResult r = render_with(scene, former, former ? old_spp : kNewSpp, uint64_t(run));
        mse[former] += bench::mse(r.image, ref) / kRuns;
        seconds[former] += r.stats.seconds / kRuns;
        paths[former] += double(r.stats.paths) / r.stats.seconds / kRuns;
      }
  state.SetLabel(scene);
  state.counters["new_spp"] = kNewSpp;
  state.counters["former_spp"] = old_spp;
  state.counters["new_MSE"] = mse[0];
  state.counters["former_MSE"] = mse[1];
  state.counters["new_paths_per_s"] = paths[0];
  state.counters["former_paths_per_s"] = paths[1];
  state.counters["mse_ratio"] = (mse[1] * seconds[1]) / (mse[0] * seconds[0]);
}
BENCHMARK(BM_DefaultsEqualTime)->DenseRange(0, 3)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

}  // namespace
}  // namespace caligo
