// The light tree against the former tree (tree-fixed-share: no adaptive splitting, lights at
// infinity by a fixed power share) and against power-proportional and uniform selection at
// EQUAL TIME on `many-lamps` (1,000 point and spot lights in fog over a town), `stage`,
// `default` and `lights-showcase`, at 96x54.
//
// A converged reference (tree, 2048 spp) is rendered once per scene and cached in the build
// folder (bench/<scene>_reference_96x54_2048.exr; delete it after changing the scene or the
// integrator). Each sampler first renders a short calibration to measure its seconds per
// spp; the tree then renders kTreeSpp and the others the spp that takes the same time.
// Renders of the samplers alternate (kRuns rounds, new seed each), so load from other
// processes hits them alike. Counters: MSE against the reference and seconds, per sampler,
// and mse_ratio = MSE(other) / MSE(tree) at equal time, computed from MSE x seconds (MSE of an
// unbiased estimator falls as 1 / time), so the small residual difference in time cancels.
// tree_mean_diff and other_mean_diff (image mean minus the reference's) watch for bias.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <string>

#include "bench_reference.h"
#include "bench_scene.h"
#include "image/compare.h"
#include "image/exr_io.h"
#include "render/render.h"

namespace caligo {
namespace {

constexpr Vec2i kResolution{96, 54};
constexpr int kReferenceSpp = 2048;
constexpr int kTreeSpp = 32;
constexpr int kRuns = 8;

const char* const kScenes[] = {"many-lamps", "stage", "default", "lights-showcase"};

RenderSettings lamp_settings(const char* scene, LightSamplerKind kind, int spp, uint64_t seed) {
  RenderSettings s = render_settings(bench::builtin_scene(scene).desc());
  s.resolution = kResolution;
  s.spp = spp;
  s.seed = seed;
  s.path.light_sampler = kind;
  return s;
}

Image reference(const char* scene) {
  std::string stem = scene;
  std::replace(stem.begin(), stem.end(), '-', '_');
  return bench::cached_reference(stem + "_reference", kResolution, kReferenceSpp, [&] {
    return render(bench::builtin_scene(scene), lamp_settings(scene, LightSamplerKind::kTree, kReferenceSpp, 777)).image;
  });
}

struct Measure {
  const Image& ref;
  double mse = 0.0, seconds = 0.0, mean_difference = 0.0;
  int renders = 0;
  void add(const RenderResult& r) {
    const ImageMetrics m = compare_images(r.image, ref);
    mse += m.rmse * m.rmse;
    mean_difference += m.mean_difference;
    seconds += r.stats.seconds;
    ++renders;
  }
  double mean_mse() const { return mse / renders; }
  double mean_seconds() const { return seconds / renders; }
};

double seconds_per_spp(const char* scene, LightSamplerKind kind) {
  const RenderResult r = render(bench::builtin_scene(scene), lamp_settings(scene, kind, 8, 99));
  return r.stats.seconds / 8.0;
}

// range(0): the scene (kScenes); range(1): the sampler compared with the tree.
void BM_LightTreeEqualTime(benchmark::State& state) {
  const char* name = kScenes[state.range(0)];
  const auto other = LightSamplerKind(state.range(1));
  const Scene& scene = bench::builtin_scene(name);
  const Image ref = reference(name);
  const double tree_rate = seconds_per_spp(name, LightSamplerKind::kTree), other_rate = seconds_per_spp(name, other);
  const int other_spp = std::max(1, int(std::lround(kTreeSpp * tree_rate / other_rate)));
  Measure tree{ref}, them{ref};
  for (auto _ : state) {
    for (int run = 0; run < kRuns; ++run) {
      tree.add(render(scene, lamp_settings(name, LightSamplerKind::kTree, kTreeSpp, uint64_t(run))));
      them.add(render(scene, lamp_settings(name, other, other_spp, uint64_t(run))));
    }
  }
  state.SetLabel(std::string(name) + " vs " + light_sampler_name(other));
  state.counters["tree_spp"] = kTreeSpp;
  state.counters["other_spp"] = other_spp;
  state.counters["tree_s"] = tree.mean_seconds();
  state.counters["other_s"] = them.mean_seconds();
  state.counters["tree_MSE"] = tree.mean_mse();
  state.counters["other_MSE"] = them.mean_mse();
  // Bias check (the reference is the tree's own): image mean minus the reference's, per sampler.
  state.counters["tree_mean_diff"] = tree.mean_difference / tree.renders;
  state.counters["other_mean_diff"] = them.mean_difference / them.renders;
  state.counters["mse_ratio"] =
      (them.mean_mse() * them.mean_seconds()) / (tree.mean_mse() * tree.mean_seconds());
}
BENCHMARK(BM_LightTreeEqualTime)
    ->ArgNames({"scene", "other"})
    ->Args({0, int(LightSamplerKind::kTreeFixedShare)})
    ->Args({0, int(LightSamplerKind::kPower)})
    ->Args({0, int(LightSamplerKind::kUniform)})
    ->Args({1, int(LightSamplerKind::kTreeFixedShare)})
    ->Args({2, int(LightSamplerKind::kTreeFixedShare)})
    ->Args({3, int(LightSamplerKind::kTreeFixedShare)})
    ->Args({3, int(LightSamplerKind::kUniform)})
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(1);

// Tree construction over the town's lights (done once per Scene::build).
void BM_LightTreeBuild(benchmark::State& state) {
  const Scene& scene = bench::builtin_scene("many-lamps");
  for (auto _ : state) {
    LightSampler tree(LightSamplerKind::kTree, scene.lights());
    benchmark::DoNotOptimize(tree);
  }
}
BENCHMARK(BM_LightTreeBuild)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace caligo
