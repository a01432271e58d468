// Throughput of the sampling kernels every path vertex calls: a 2D sampler request, a cosine
// hemisphere warp, and a light pick from a discrete distribution.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <vector>

#include "core/rng.h"
#include "core/sampler.h"
#include "core/sampling.h"

namespace caligo {
namespace {

void BM_SamplerGet2D(benchmark::State& state) {
  uint32_t index = 0;
  for (auto _ : state) {
    const Sampler sampler(42, {int(index & 255u), int(index >> 8 & 255u)}, index);
    benchmark::DoNotOptimize(sampler.get_2d(sample_dim::bounce(1, sample_dim::kBsdfDirection)));
    ++index;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_SamplerGet2D);

void BM_SampleCosineHemisphere(benchmark::State& state) {
  Pcg32 rng;
  for (auto _ : state) {
    const Vec2 u{rng.next_float(), rng.next_float()};
    benchmark::DoNotOptimize(sample_cosine_hemisphere(u));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_SampleCosineHemisphere);

// state.range(0) weights, e.g. one per light.
void BM_DiscreteDistributionSample(benchmark::State& state) {
  Pcg32 rng(1, 2);
  std::vector<float> weights(size_t(state.range(0)));
  for (float& w : weights) w = rng.next_float();
  const DiscreteDistribution distribution(weights);
  for (auto _ : state) {
    float pmf = 0.0f, remapped = 0.0f;
    benchmark::DoNotOptimize(distribution.sample(rng.next_float(), &pmf, &remapped));
    benchmark::DoNotOptimize(pmf);
    benchmark::DoNotOptimize(remapped);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_DiscreteDistributionSample)->Arg(8)->Arg(1024)->Arg(65536);

}  // namespace
}  // namespace caligo
