// Nested media (issue 9): what the medium stack costs.
//   BM_NestedOverhead/0 and /1: the default scene as is, and with one priority surface no ray
//     meets (inside its floor), which switches every path onto the nested code (stack copies,
//     deferred shadow queries) without changing the image: the ratio is the stack's overhead on
//     a scene that does not use it. Without priority surfaces the nested code is skipped by one
//     flag test per segment.
//   BM_NestedMediaPerRay/N: camera rays through N concentric spheres bounding media of
//     increasing priority inwards (every boundary is a real crossing, the medium changes at each),
//     against N = 0 (the same camera, no spheres): the cost per ray of crossing N nested media.
// Run: build/release/bench/caligo_bench --benchmark_filter=Nested
#include <benchmark/benchmark.h>

#include "bench_scene.h"
#include "render/render.h"

namespace caligo {
namespace {

void BM_NestedOverhead(benchmark::State& state) {
  SceneDesc desc = bench::builtin_scene("default").desc();
  if (state.range(0)) {
    desc.media.push_back({"unmet", VolumeShader{RGB(1.0f), RGB(0.0f)}});
    Material boundary;
    boundary.name = "unmet";
    boundary.bsdf = NullBsdf{};
    boundary.priority = kPriorityNormal;
    boundary.interior = int(desc.media.size()) - 1;
    desc.materials.push_back(boundary);
    // Under the closed room's floor, where no ray goes (the scene has no infinite light, so the
    // slightly larger bounds change no light's selection probability).
    ShapeDesc box;
    box.geometry = BoxShape{{-0.05f, -0.5f, -0.05f}, {0.05f, -0.4f, 0.05f}};
    box.material = int(desc.materials.size()) - 1;
    desc.shapes.push_back(box);
  }
  const auto scene = Scene::build(desc);
  RenderSettings settings = render_settings(desc);
  settings.resolution = {160, 120};
  settings.spp = 16;
  uint64_t paths = 0;
  for (auto _ : state) paths += render(*scene, settings).stats.paths;
  state.counters["paths/s"] = benchmark::Counter(double(paths), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_NestedOverhead)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);

void BM_NestedMediaPerRay(benchmark::State& state) {
  const int n = int(state.range(0));
  SceneDesc desc;
  desc.file = "bench";
  desc.camera = {{0, 0, 6}, {0, 0, 0}, {0, 1, 0}, 20.0f, {64, 64}};
  for (int i = 0; i < n; ++i) {
    desc.media.push_back({std::string("m") + std::to_string(i), VolumeShader{RGB(0.01f), RGB(0.0f)}});
    Material m;
    m.name = std::string("shell") + std::to_string(i);
    m.bsdf = NullBsdf{};
    m.priority = 400 - 20 * i;  // inner spheres higher: each boundary is real
    m.interior = i;
    desc.materials.push_back(m);
    ShapeDesc s;
    s.geometry = SphereShape{{0, 0, 0}, 2.0f - 1.9f * float(i) / float(std::max(n, 1))};
    s.material = i;
    desc.shapes.push_back(s);
  }
  desc.lights.push_back(EnvironmentLight{RGB(1.0f)});
  const auto scene = Scene::build(desc);
  RenderSettings settings = render_settings(desc);
  settings.spp = 16;
  settings.path.limits.max_bounces = 1;
  uint64_t paths = 0;
  for (auto _ : state) paths += render(*scene, settings).stats.paths;
  state.counters["rays/s"] = benchmark::Counter(double(paths), benchmark::Counter::kIsRate);
  state.counters["ns/ray"] =
      benchmark::Counter(double(paths), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_NestedMediaPerRay)->Arg(0)->Arg(1)->Arg(4)->Arg(16)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace caligo
