// The airlight model (src/hybrid/airlight.h): building the tables, the closed form per pixel
// and one march step's lookup, with the Sun et al. table and with the per-frame table.
#include <benchmark/benchmark.h>

#include <vector>

#include "core/rng.h"
#include "hybrid/airlight.h"

namespace caligo {
namespace {

constexpr AirlightMedium kFog{0.08f, 0.1f};
const Vec3 kEye(0.0f, 1.5f, 0.0f), kLight(2.0f, 4.0f, -6.0f);

std::vector<Vec3> random_directions(int count) {
  Pcg32 rng(3, 7);
  std::vector<Vec3> dirs;
  while (int(dirs.size()) < count) {
    const Vec3 v(rng.next_float() * 2 - 1, rng.next_float() * 2 - 1, rng.next_float() * 2 - 1);
    if (length_squared(v) > 1e-4f && length_squared(v) <= 1.0f) dirs.push_back(normalize(v));
  }
  return dirs;
}

void BM_AirlightTableBuild(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(AirlightTable(AirlightTable::Options{}));
}
BENCHMARK(BM_AirlightTableBuild)->Unit(benchmark::kMillisecond);

void BM_AirlightTableF(benchmark::State& state) {
  const AirlightTable& table = AirlightTable::shared();
  float u = 0.1f, v = 0.2f;
  for (auto _ : state) {
    benchmark::DoNotOptimize(table.F(u, v));
    u = u > 20.0f ? 0.1f : u * 1.01f;
    v = v > 1.5f ? 0.2f : v + 0.001f;
  }
}
BENCHMARK(BM_AirlightTableF);

// The whole closed form for one pixel: per-ray constants and the airlight from the eye to a surface.
void BM_AirlightClosedFormPixel(benchmark::State& state) {
  const AirlightTable& table = AirlightTable::shared();
  const auto dirs = random_directions(4096);
  size_t i = 0;
  for (auto _ : state) {
    const AirlightRay ray = make_airlight_ray(table, kFog, 100.0f, kLight, kEye, dirs[i++ & 4095]);
    benchmark::DoNotOptimize(airlight(table, ray, 20.0f));
  }
  state.SetItemsProcessed(int64_t(state.iterations()));
}
BENCHMARK(BM_AirlightClosedFormPixel);

// One march step with the closed form: the tail at the step's far end (the near end is the previous step's).
void BM_AirlightTailStep(benchmark::State& state) {
  const AirlightTable& table = AirlightTable::shared();
  const AirlightRay ray =
      make_airlight_ray(table, kFog, 100.0f, kLight, kEye, normalize(Vec3(0.3f, 0.4f, -1.0f)));
  float t = 0.0f;
  for (auto _ : state) {
    benchmark::DoNotOptimize(airlight_tail(table, ray, t));
    t = t > 30.0f ? 0.0f : t + 0.2f;
  }
}
BENCHMARK(BM_AirlightTailStep);

void BM_FrameAirlightBuild(benchmark::State& state) {
  const AirlightTable& table = AirlightTable::shared();
  for (auto _ : state) benchmark::DoNotOptimize(FrameAirlight(table, kFog, 100.0f, kLight, kEye));
}
BENCHMARK(BM_FrameAirlightBuild)->Unit(benchmark::kMicrosecond);

// One march step with the per-frame table: one lookup (the subtraction and multiply are the caller's).
void BM_FrameAirlightStep(benchmark::State& state) {
  const FrameAirlight frame(AirlightTable::shared(), kFog, 100.0f, kLight, kEye);
  const FrameAirlight::Ray ray = frame.ray(normalize(Vec3(0.3f, 0.4f, -1.0f)));
  float t = 0.0f;
  for (auto _ : state) {
    benchmark::DoNotOptimize(frame.cumulative(ray, t));
    t = t > 30.0f ? 0.0f : t + 0.2f;
  }
}
BENCHMARK(BM_FrameAirlightStep);

void BM_FrameAirlightPixel(benchmark::State& state) {
  const FrameAirlight frame(AirlightTable::shared(), kFog, 100.0f, kLight, kEye);
  const auto dirs = random_directions(4096);
  size_t i = 0;
  for (auto _ : state) {
    const FrameAirlight::Ray ray = frame.ray(dirs[i++ & 4095]);
    benchmark::DoNotOptimize(frame.interval(ray, 0.0f, 20.0f));
  }
  state.SetItemsProcessed(int64_t(state.iterations()));
}
BENCHMARK(BM_FrameAirlightPixel);

}  // namespace
}  // namespace caligo
