// Deferred next-event estimation (PathSettings::deferred_nee) against per-segment NEE at EQUAL
// TIME on a dense multiple-scattering scene: a sphere of albedo 0.99, extinction 8 per metre
// (radius 1 m: ~16 mean free paths across), HG 0.5, lit by a point light beside it and a sky.
// The reference (per-segment NEE, kReferenceSpp) is cached in the build folder
// (bench/deferred_nee_reference_64x48_SPP.exr). Counters: MSE and seconds per strategy and
// mse_ratio = MSE(deferred) / MSE(per-segment) at equal time (from MSE x seconds): below 1 the
// deferred form wins. Run: build/release/bench/caligo_bench --benchmark_filter=DeferredNee
#include <benchmark/benchmark.h>

#include "bench_reference.h"

#include <filesystem>
#include <string>

#include "image/compare.h"
#include "image/exr_io.h"
#include "render/render.h"

namespace caligo {
namespace {

constexpr Vec2i kResolution{64, 48};
constexpr int kReferenceSpp = 2048;
constexpr int kSpp = 32;
constexpr int kRuns = 3;

const Scene& dense_scene() {
  static const std::unique_ptr<Scene> scene = [] {
    SceneDesc desc;
    desc.file = "bench";
    desc.camera = {{0, 0, 4}, {0, 0, 0}, {0, 1, 0}, 40.0f, kResolution};
    VolumePrimitive v{SphereVolumeShape{Sphere::make({0, 0, 0}, 1.0f, {})}, {RGB(0.08f), RGB(7.92f)}};
    v.shader.phase = HenyeyGreensteinPhase{0.5f};
    desc.volumes.push_back(v);
    desc.lights.push_back(PointLight{{2.0f, 1.5f, 1.0f}, RGB(20.0f)});
    desc.lights.push_back(EnvironmentLight{RGB(0.2f, 0.25f, 0.3f)});
    return Scene::build(desc);
  }();
  return *scene;
}

RenderSettings settings(int deferred, int spp, uint64_t seed) {
  RenderSettings s = render_settings(dense_scene().desc());
  s.spp = spp;
  s.seed = seed;
  s.path.limits.max_volume_bounces = 256;
  s.path.deferred_nee = deferred;
  return s;
}

const Image& reference() {
  static const Image image = bench::cached_reference("deferred_nee_reference", kResolution, kReferenceSpp, [] {
    return render(dense_scene(), settings(0, kReferenceSpp, 777)).image;
  });
  return image;
}

// range(0): connections per path of the deferred form.
void BM_DeferredNeeEqualTime(benchmark::State& state) {
  const int k = int(state.range(0));
  reference();
  double mse[2] = {0, 0}, seconds[2] = {0, 0};
  for (auto _ : state)
    for (int run = 0; run < kRuns; ++run)
      for (int deferred = 0; deferred < 2; ++deferred) {
        const RenderResult r = render(dense_scene(), settings(deferred ? k : 0, kSpp, uint64_t(run)));
        mse[deferred] += bench::mse(r.image, reference()) / kRuns;
        seconds[deferred] += r.stats.seconds / kRuns;
      }
  state.counters["per_segment_MSE"] = mse[0];
  state.counters["deferred_MSE"] = mse[1];
  state.counters["per_segment_s"] = seconds[0];
  state.counters["deferred_s"] = seconds[1];
  state.counters["mse_ratio"] = (mse[1] * seconds[1]) / (mse[0] * seconds[0]);
}
BENCHMARK(BM_DeferredNeeEqualTime)->Arg(1)->Arg(4)->Arg(16)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

}  // namespace
}  // namespace caligo
