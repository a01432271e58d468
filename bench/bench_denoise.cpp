// The denoiser on a 1920x1080 frame of synthetic layers (issue 25's target: at most 2 s on two
// cores). Run: build/release/bench/caligo_bench --benchmark_filter=Denoise
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>

#include "denoise/denoise.h"

namespace caligo {
namespace {

DenoiseLayers frame(int w, int h) {
  DenoiseLayers d;
  d.width = w;
  d.height = h;
  const size_t n = size_t(w) * size_t(h);
  std::mt19937 rng(3);
  std::normal_distribution<float> noise(0.0f, 0.1f);
  for (int c = 0; c < 3; ++c) {
    d.half_a[size_t(c)].resize(n);
    d.half_b[size_t(c)].resize(n);
  }
  d.variance.assign(n, 0.005f);
  for (auto& f : d.features) f.resize(n);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * size_t(w) + size_t(x);
      const float t = 0.3f + 0.2f * std::sin(0.01f * float(x)) + (y > h / 2 ? 0.3f : 0.0f);
      for (int c = 0; c < 3; ++c) d.half_a[size_t(c)][i] = t + noise(rng), d.half_b[size_t(c)][i] = t + noise(rng);
      for (int f = 0; f < kDenoiseFeatures; ++f) d.features[size_t(f)][i] = f == 6 ? (y > h / 2 ? 1.0f : 0.0f) : 0.5f;
    }
  return d;
}

void BM_Denoise1080p(benchmark::State& state) {
  const DenoiseLayers layers = frame(1920, 1080);
  DenoiseSettings settings;
  settings.radius = int(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(denoise(layers, settings).image.data());
  state.SetLabel("radius " + std::to_string(settings.radius));
}
BENCHMARK(BM_Denoise1080p)->Arg(4)->Arg(5)->Arg(3)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);

}  // namespace
}  // namespace caligo
