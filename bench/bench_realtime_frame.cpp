// Whole real-time frames of scenes/arena.json at 1920x1080 with quarter-resolution
// accumulation (the target: accumulation + gather + upsample + temporal <= 33 ms),
// and how accumulation grows with the number of volumetric lights (1, 7, 32): the light
// list is the arena's seven lights, cut or repeated with small offsets. BM_RealtimeArena1080pFroxel
// is the same frames by `--method froxel` (the 160x90x64 grid in place of the per-light march):
// the ratio of the two volumetric_us counters is the one to quote.
// Counters are medians over the timed frames, in microseconds.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <vector>

#include "realtime/pipeline.h"
#include "scene/scene.h"
#include "scene/scene_parser.h"

#ifndef CALIGO_SCENES_DIR
#error "CALIGO_SCENES_DIR must name the scenes folder"
#endif

namespace caligo {
namespace {

SceneDesc arena_with_lights(int count) {
  SceneDesc desc = parse_scene_file(std::string(CALIGO_SCENES_DIR) + "/arena.json");
  const std::vector<Light> base = desc.lights;
  const std::vector<LightOptions> base_options = desc.light_options;
  desc.lights.clear();
  desc.light_options.clear();
  for (int i = 0; i < count; ++i) {
    Light light = base[size_t(i) % base.size()];
    // Repeated lights move a little so that they are distinct lights with distinct shadow maps.
    const float shift = 0.4f * float(i / int(base.size()));
    std::visit([shift](auto& l) {
      if constexpr (requires { l.position; }) l.position.x += shift;
    }, light);
    desc.lights.push_back(light);
    desc.light_options.push_back(base_options[size_t(i) % base.size()]);
  }
  return desc;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

void run_frames(benchmark::State& state, int lights, bool simd, bool froxel = false) {
  const SceneDesc desc = arena_with_lights(lights);
  RealtimeSettings settings = realtime_settings(desc);
  settings.resolution = {1920, 1080};
  settings.scale = 4;
  settings.simd = simd;
  settings.froxel = froxel;
  RealtimePipeline pipeline(Scene::build(desc), settings);
  for (int warm = 0; warm < 2; ++warm) pipeline.render(0.0f, uint32_t(warm));
  std::vector<double> acc, gather, up, temporal, volumetric, total;
  uint32_t frame = 2;
  for (auto _ : state) {
    const RealtimeFrame& f = pipeline.render(float(frame) / 30.0f, frame);
    ++frame;
    acc.push_back(f.times.accumulation);
    gather.push_back(f.times.gather);
    up.push_back(f.times.upsample);
    temporal.push_back(f.times.temporal);
    volumetric.push_back(f.times.volumetric());
    total.push_back(f.times.total);
  }
  state.counters["accum_us"] = median(acc);
  state.counters["gather_us"] = median(gather);
  state.counters["upsample_us"] = median(up);
  state.counters["temporal_us"] = median(temporal);
  state.counters["volumetric_us"] = median(volumetric);
  state.counters["frame_us"] = median(total);
  state.counters["accum_per_light_us"] = median(acc) / lights;
}

void BM_RealtimeArena1080p(benchmark::State& state) { run_frames(state, int(state.range(0)), true); }
BENCHMARK(BM_RealtimeArena1080p)->Arg(1)->Arg(7)->Arg(32)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(12);

void BM_RealtimeArena1080pFroxel(benchmark::State& state) { run_frames(state, int(state.range(0)), true, true); }
BENCHMARK(BM_RealtimeArena1080pFroxel)->Arg(7)->Arg(32)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(12);

void BM_RealtimeArena1080pScalar(benchmark::State& state) { run_frames(state, 7, false); }
BENCHMARK(BM_RealtimeArena1080pScalar)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(6);

}  // namespace
}  // namespace caligo
