// The secondary-segment estimators (issue 18) against the former behaviour in the same binary,
// each scene at EQUAL TIME against a converged reference rendered with march (kReferenceSpp,
// cached in the build folder as bench/secondary_reference_NAME_80x60_SPP.exr; delete it after
// changing the scene or the integrator). The variants:
//   former: every segment marched, emission found by bounce rays alone (before issue 18);
//   ratio:  PathSettings::secondary = auto with plain ratio tracking, emission unsampled;
//   auto:   the default (auto, residual ratio tracking, emissive grids sampled as lights);
//   track:  tracking everywhere, with the default's other settings.
// Counters per variant: MSE, seconds, paths/s and shader evaluations per path; efficiency =
// (MSE x seconds)(former) / (MSE x seconds)(variant), the factor by which it reaches a given
// error sooner (the MSE of an unbiased estimator falls as 1 / time); mean_offset = its image
// mean minus the reference's, relative (a bias would show here).
// Run: build/release/bench/caligo_bench --benchmark_filter=SecondaryEqualTime
#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>

#include "bench_reference.h"
#include "bench_scene.h"
#include "image/compare.h"
#include "image/exr_io.h"
#include "render/render.h"

namespace caligo {
namespace {

constexpr Vec2i kResolution{80, 60};
constexpr int kReferenceSpp = 1024;
constexpr int kMarchSpp = 96;
constexpr int kRuns = 3;

const char* const kScenes[] = {"cloud",       "cloud-dense", "smoke", "fire",          "lamp-in-fog",
                               "default",     "stage",       "spot-shafts", "glass-of-water"};
struct Variant {
  const char* name;
  SecondarySegments secondary;
  bool residual_ratio_tracking, sample_emission;
};
constexpr Variant kVariants[] = {{"former", SecondarySegments::kMarch, true, false},
                                 {"ratio", SecondarySegments::kAuto, false, false},
                                 {"auto", SecondarySegments::kAuto, true, true},
                                 {"track", SecondarySegments::kTrack, true, true}};
constexpr int kVariantCount = int(std::size(kVariants));

RenderResult render_with(const char* scene, const Variant& v, int spp, uint64_t seed) {
  RenderSettings s = render_settings(bench::builtin_scene(scene).desc());
  s.resolution = kResolution;
  s.spp = spp;
  s.seed = seed;
  s.path.secondary = v.secondary;
  s.path.residual_ratio_tracking = v.residual_ratio_tracking;
  s.path.sample_emission = v.sample_emission;
  return render(bench::builtin_scene(scene), s);
}

Image reference(const char* scene) {
  return bench::cached_reference(std::string("secondary_reference_") + scene, kResolution, kReferenceSpp,
                                 [&] { return render_with(scene, kVariants[0], kReferenceSpp, 4242).image; });
}

double image_mean(const Image& image) {
  double sum = 0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) sum += image.rgb(x, y, 0).average();
  return sum / (double(image.width()) * image.height());
}

void BM_SecondaryEqualTime(benchmark::State& state) {
  const char* scene = kScenes[state.range(0)];
  const Image ref = reference(scene);
  const double ref_mean = image_mean(ref);
  // Samples per pixel for equal time, from a short run of each variant after one to warm up
  // (the first render of a scene pays for what is built on first use, which made the former's
  // rate look up to 20x slower than it is).
  render_with(scene, kVariants[0], 2, 98);
  double rate[kVariantCount];
  for (int m = 0; m < kVariantCount; ++m) rate[m] = render_with(scene, kVariants[m], 8, 99).stats.seconds / 8.0;
  double mse[kVariantCount] = {}, seconds[kVariantCount] = {}, paths_per_s[kVariantCount] = {},
         evals[kVariantCount] = {}, offset[kVariantCount] = {};
  int spp[kVariantCount];
  for (int m = 0; m < kVariantCount; ++m) spp[m] = std::max(1, int(std::lround(kMarchSpp * rate[0] / rate[m])));
  for (auto _ : state)
    for (int run = 0; run < kRuns; ++run)
      for (int m = 0; m < kVariantCount; ++m) {
        const RenderResult r = render_with(scene, kVariants[m], spp[m], uint64_t(run) + 1);
        mse[m] += bench::mse(r.image, ref) / kRuns;
        seconds[m] += r.stats.seconds / kRuns;
        paths_per_s[m] += double(r.stats.paths) / r.stats.seconds / kRuns;
        evals[m] += double(r.stats.shader_evaluations) / double(r.stats.paths) / kRuns;
        offset[m] += (image_mean(r.image) - ref_mean) / ref_mean / kRuns;
      }
  state.SetLabel(scene);
  for (int m = 0; m < kVariantCount; ++m) {
    const std::string n = kVariants[m].name;
    state.counters[n + "_spp"] = spp[m];
    state.counters[n + "_MSE"] = mse[m];
    state.counters[n + "_s"] = seconds[m];
    state.counters[n + "_paths_per_s"] = paths_per_s[m];
    state.counters[n + "_evals_per_path"] = evals[m];
    state.counters[n + "_mean_offset"] = offset[m];
    if (m > 0) state.counters[n + "_efficiency"] = (mse[0] * seconds[0]) / (mse[m] * seconds[m]);
  }
}
BENCHMARK(BM_SecondaryEqualTime)->DenseRange(0, 8)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

}  // namespace
}  // namespace caligo
