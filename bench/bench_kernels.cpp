// Ray queries against the default scene: closest hit, occlusion and all hits per second.
#include <benchmark/benchmark.h>

#include "bench_scene.h"
#include "core/rng.h"
#include "core/sampling.h"

namespace caligo {
namespace {

// Rays from the camera position in uniformly random directions: every one hits the closed room.
std::vector<Ray> random_rays(const Scene& scene, int count) {
  Pcg32 rng(1, 1);
  const Vec3 origin = scene.desc().camera.position;
  std::vector<Ray> rays;
  for (int i = 0; i < count; ++i)
    rays.push_back({origin, sample_uniform_sphere({rng.next_float(), rng.next_float()})});
  return rays;
}

void BM_ClosestHit(benchmark::State& state) {
  const Scene& scene = bench::builtin_scene("default");
  const auto rays = random_rays(scene, 4096);
  size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(scene.surfaces().intersect(rays[i++ & 4095]));
  state.SetItemsProcessed(int64_t(state.iterations()));
}
BENCHMARK(BM_ClosestHit);

void BM_Occluded(benchmark::State& state) {
  const Scene& scene = bench::builtin_scene("default");
  auto rays = random_rays(scene, 4096);
  for (Ray& r : rays) r.tmax = 1.0f;
  size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(scene.surfaces().occluded(rays[i++ & 4095]));
  state.SetItemsProcessed(int64_t(state.iterations()));
}
BENCHMARK(BM_Occluded);

void BM_AllHits(benchmark::State& state) {
  const Scene& scene = bench::builtin_scene("default");
  const auto rays = random_rays(scene, 4096);
  std::vector<SurfaceHit> hits;
  size_t i = 0;
  for (auto _ : state) {
    scene.surfaces().all_hits(rays[i++ & 4095], hits);
    benchmark::DoNotOptimize(hits.data());
  }
  state.SetItemsProcessed(int64_t(state.iterations()));
}
BENCHMARK(BM_AllHits);

}  // namespace
}  // namespace caligo
