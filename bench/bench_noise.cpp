// Path guiding, adaptive sampling and the sample clamp against the same renderer without them, in
// the same binary (issue 21; docs/noise.md). Each scene's converged reference (unguided, kReferenceSpp) is cached in the build
// folder (bench/guiding_reference_NAME_96x72_SPP.exr; delete it after changing the scene or the
// integrator). Counters: each mode's MSE and seconds over kRuns seeds, and gain = MSE x seconds
// (off) / MSE x seconds (on): above 1 the feature wins at equal time (the MSE of an unbiased
// estimator falls as 1 / time; a guided render's falls faster once trained, so the gain at
// higher sample counts is at least this). Guiding's counters also give the field's memory and
// the share of the render's time its samples took beyond the unguided ones' (training and
// guided sampling together: overhead = seconds(on) / seconds(off) - 1).
// Run: build/release/bench/caligo_bench --benchmark_filter='GuidingEqualTime|AdaptiveEqualTime|ClampFireflies'
#include <benchmark/benchmark.h>

#include <algorithm>
#include <string>
#include <vector>

#include "bench_reference.h"
#include "bench_scene.h"
#include "render/render.h"

namespace caligo {
namespace {

constexpr Vec2i kResolution{96, 72};
constexpr int kRuns = 3;

struct Case {
  const char* scene;
  int spp, reference_spp;
};

const Case kGuided[] = {{"lamp-in-fog", 256, 8192}, {"cloud", 128, 2048},   {"default", 128, 4096},
                        {"stage", 64, 2048},        {"many-lamps", 32, 1024}, {"hdri-fog", 64, 2048},
                        {"glass-of-water", 64, 2048}, {"sss", 64, 2048}};

RenderSettings settings_for(const char* scene, int spp, uint64_t seed) {
  RenderSettings s = render_settings(bench::builtin_scene(scene).desc());
  s.resolution = kResolution;
  s.spp = spp;
  s.seed = seed;
  return s;
}

Image reference(const Case& c) {
  return bench::cached_reference(std::string("guiding_reference_") + c.scene, kResolution, c.reference_spp,
                                 [&] { return render(bench::builtin_scene(c.scene), settings_for(c.scene, c.reference_spp, 777)).image; });
}

struct Measured {
  double mse = 0.0, seconds = 0.0;
  RenderStats::Guiding field;
};

template <typename Configure>
Measured measure(const char* scene, int spp, const Image& ref, Configure&& configure) {
  Measured m;
  for (int run = 0; run < kRuns; ++run) {
    RenderSettings s = settings_for(scene, spp, uint64_t(run + 1));
    configure(s);
    const RenderResult r = render(bench::builtin_scene(scene), s);
    m.mse += bench::mse(r.image, ref) / kRuns;
    m.seconds += r.stats.seconds / kRuns;
    m.field = r.stats.guiding;
  }
  return m;
}

void BM_GuidingEqualTime(benchmark::State& state) {
  const Case& c = kGuided[state.range(0)];
  const Image ref = reference(c);
  Measured off, on;
  for (auto _ : state) {
    off = measure(c.scene, c.spp, ref, [](RenderSettings& s) { s.path.guiding = GuidingMode::kOff; });
    on = measure(c.scene, c.spp, ref, [](RenderSettings& s) { s.path.guiding = GuidingMode::kAll; });
  }
  state.SetLabel(c.scene);
  state.counters["spp"] = c.spp;
  state.counters["off_MSE"] = off.mse;
  state.counters["on_MSE"] = on.mse;
  state.counters["off_s"] = off.seconds;
  state.counters["on_s"] = on.seconds;
  state.counters["gain"] = (off.mse * off.seconds) / (on.mse * on.seconds);
  state.counters["overhead"] = on.seconds / off.seconds - 1.0;
  state.counters["field_MB"] = double(on.field.bytes) / 1e6;
  state.counters["leaves"] = double(on.field.leaves);
}
BENCHMARK(BM_GuidingEqualTime)->DenseRange(0, 7)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

// Guided distances (PathSettings::guided_distances) on top of directional guiding, against
// directional guiding alone; cases 0 (lamp-in-fog) and 1 (cloud) of kGuided.
void BM_GuidedDistancesEqualTime(benchmark::State& state) {
  const Case& c = kGuided[state.range(0)];
  const Image ref = reference(c);
  Measured off, on;
  for (auto _ : state) {
    off = measure(c.scene, c.spp, ref, [](RenderSettings& s) { s.path.guiding = GuidingMode::kAll; });
    on = measure(c.scene, c.spp, ref, [](RenderSettings& s) {
      s.path.guiding = GuidingMode::kAll;
      s.path.guided_distances = true;
    });
  }
  state.SetLabel(c.scene);
  state.counters["directions_MSE"] = off.mse;
  state.counters["with_distances_MSE"] = on.mse;
  state.counters["directions_s"] = off.seconds;
  state.counters["with_distances_s"] = on.seconds;
  state.counters["gain"] = (off.mse * off.seconds) / (on.mse * on.seconds);
}
BENCHMARK(BM_GuidedDistancesEqualTime)->DenseRange(0, 1)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

// Deferred next-event estimation by segments (PathSettings::deferred_nee = range(1) connections)
// against per-segment NEE on the dense media of kGuided: case 1 (cloud) and 7 (sss);
// bench_deferred_nee.cpp has the dense sphere. gain above 1: deferred wins at equal time.
void BM_DeferredNeeScenes(benchmark::State& state) {
  const Case& c = kGuided[state.range(0)];
  const int k = int(state.range(1));
  const Image ref = reference(c);
  Measured off, on;
  for (auto _ : state) {
    off = measure(c.scene, c.spp, ref, [](RenderSettings&) {});
    on = measure(c.scene, c.spp, ref, [&](RenderSettings& s) { s.path.deferred_nee = k; });
  }
  state.SetLabel(c.scene);
  state.counters["per_segment_MSE"] = off.mse;
  state.counters["deferred_MSE"] = on.mse;
  state.counters["per_segment_s"] = off.seconds;
  state.counters["deferred_s"] = on.seconds;
  state.counters["gain"] = (off.mse * off.seconds) / (on.mse * on.seconds);
}
BENCHMARK(BM_DeferredNeeScenes)->ArgsProduct({{1, 7}, {4}})->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

// Adaptive sampling at threshold range(1) / 100 against every pixel taking every sample.
const Case kAdaptive[] = {{"default", 256, 4096}, {"holdout", 256, 4096}};

void BM_AdaptiveEqualTime(benchmark::State& state) {
  const Case& c = kAdaptive[state.range(0)];
  const float threshold = float(state.range(1)) / 100.0f;
  const Image ref = reference(c);
  Measured off, on;
  for (auto _ : state) {
    off = measure(c.scene, c.spp, ref, [](RenderSettings&) {});
    on = measure(c.scene, c.spp, ref, [threshold](RenderSettings& s) {
      s.adaptive.threshold = threshold;
      s.aovs = s.aovs.with(Aov::kVariance);
    });
  }
  state.counters["threshold"] = threshold;
  state.SetLabel(c.scene);
  state.counters["off_MSE"] = off.mse;
  state.counters["on_MSE"] = on.mse;
  state.counters["off_s"] = off.seconds;
  state.counters["on_s"] = on.seconds;
  state.counters["gain"] = (off.mse * off.seconds) / (on.mse * on.seconds);
}
BENCHMARK(BM_AdaptiveEqualTime)
    ->ArgsProduct({{0, 1}, {5, 10}})
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(1);

// Fireflies: the brightest pixel over the median one and the share of pixels above 10x the
// median, without and with a clamp of range(1) / 10 on indirect light (and 10x that on direct),
// and the clamp's bias: the change of the image mean.
struct Fireflies {
  double peak_over_median = 0.0, share_above_10x = 0.0, mean = 0.0;
};

Fireflies fireflies(const Image& image) {
  std::vector<float> lum;
  double sum = 0.0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      lum.push_back(image.rgb(x, y, 0).average());
      sum += lum.back();
    }
  std::vector<float> sorted = lum;
  std::nth_element(sorted.begin(), sorted.begin() + long(sorted.size() / 2), sorted.end());
  const double median = std::max(1e-6f, sorted[sorted.size() / 2]);
  Fireflies f;
  for (float l : lum) {
    f.peak_over_median = std::max(f.peak_over_median, double(l) / median);
    f.share_above_10x += l > 10.0 * median ? 1.0 / double(lum.size()) : 0.0;
  }
  f.mean = sum / double(lum.size());
  return f;
}

const char* const kClampScenes[] = {"underwater", "default"};

void BM_ClampFireflies(benchmark::State& state) {
  const char* scene = kClampScenes[state.range(0)];
  const float limit = float(state.range(1)) / 10.0f;
  Fireflies off, on;
  for (auto _ : state) {
    RenderSettings s = settings_for(scene, 64, 1);
    off = fireflies(render(bench::builtin_scene(scene), s).image);
    s.clamp = {.direct = 10.0f * limit, .indirect = limit};
    on = fireflies(render(bench::builtin_scene(scene), s).image);
  }
  state.SetLabel(scene);
  state.counters["indirect_clamp"] = limit;
  state.counters["off_peak_over_median"] = off.peak_over_median;
  state.counters["on_peak_over_median"] = on.peak_over_median;
  state.counters["off_share_above_10x"] = off.share_above_10x;
  state.counters["on_share_above_10x"] = on.share_above_10x;
  state.counters["mean_change"] = on.mean / off.mean - 1.0;
}
BENCHMARK(BM_ClampFireflies)->ArgsProduct({{0, 1}, {10, 30}})->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

}  // namespace
}  // namespace caligo
