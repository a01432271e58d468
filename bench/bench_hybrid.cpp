// The hybrid's scattering pass against the brute-force march (issue 8): one point light in fog
// over a ground plane with an 81,920-triangle icosphere occluder, at 256² and 1024². The
// hybrid marches 50 steps only where the shadow volumes cover the pixel; the brute force 150
// steps everywhere (the paper's settings). Counters: shadow-map lookups per pixel and the
// fraction of pixels marched. The second argument: lit runs by the closed-form tail (0, the former
// behaviour and the default) or by the per-frame table (1, HybridSettings::frame_table).
// BM_TexturedSpotModel: the textured-spotlight pass over the same scene with a spot above the
// sphere, by model (0: the airlight, once per channel in a coloured medium, the former
// behaviour; 1: Hoffman & Preetham in one pass) and medium (0: grey; 1: coloured), shadow map
// read at every step.
// Run: build/release/bench/caligo_bench --benchmark_filter=Scatter
#include <benchmark/benchmark.h>

#include <memory>
#include <vector>

#include "hybrid/hybrid_scatter.h"
#include "hybrid/textured_spot.h"
#include "hybrid/shadow_volume_testing.h"
#include "realtime/scene_buffers.h"

namespace caligo {
namespace {

struct BenchScene {
  View view;
  Plane depth;
  ShadowMap shadow;
  ShadowVolume volume;
  ShadowVolumeBuffers buffers;
  HybridLight light{{2.0f, 6.0f, 1.0f}, 20.0f, RGB(1.0f)};
  AirlightMedium medium{0.1f, 0.15f};
};

const BenchScene& scene(int res) {
  static std::vector<std::unique_ptr<BenchScene>> cache;
  for (const auto& s : cache)
    if (s->view.resolution.x == res) return *s;
  auto s = std::make_unique<BenchScene>();
  const TriangleMesh occluder = testing::sphere_mesh({0, 1.5f, 0}, 1.0f, 6);  // 81,920 triangles
  RasterScene raster;
  const Vec3 up{0, 1, 0};
  raster.add_triangle({-20, 0, -20}, {-20, 0, 20}, {20, 0, 20}, up, up, up, 0);
  raster.add_triangle({-20, 0, -20}, {20, 0, 20}, {20, 0, -20}, up, up, up, 0);
  const auto& p = occluder.positions;
  for (size_t i = 0; i + 2 < p.size(); i += 3) raster.add_triangle(p[i], p[i + 1], p[i + 2], up, up, up, 0);
  s->view = View::perspective_view({0, 3, 8}, normalize(Vec3(0, -2.2f, -8)), up, radians(50.0f), {res, res});
  s->depth = rasterize_depth(raster, s->view);
  s->shadow = *render_shadow_map(raster, PointLight{s->light.position, RGB(1.0f)}, 1024, raster.bounds());
  s->volume = build_shadow_volume(MeshEdges(occluder), s->light.position,
                                  extrusion_for(raster.bounds(), s->light.position));
  s->buffers = rasterize_shadow_volumes({&s->volume, 1}, s->view, s->depth);
  cache.push_back(std::move(s));
  return *cache.back();
}

HybridSettings settings_of(const benchmark::State& state) {
  HybridSettings h;
  h.frame_table = state.range(1) != 0;
  return h;
}

void report(benchmark::State& state, const ScatterResult& r) {
  const double pixels = double(r.lookups.size());
  state.counters["lookups_per_pixel"] = double(r.total_lookups) / pixels;
  state.counters["marched_fraction"] = double(r.marched_pixels) / pixels;
}

void BM_HybridScatter(benchmark::State& state) {
  const BenchScene& s = scene(int(state.range(0)));
  ScatterResult r;
  for (auto _ : state)
    r = scatter_hybrid(s.view, s.depth, s.buffers, s.shadow, AirlightTable::shared(), s.medium, s.light,
                       settings_of(state));
  report(state, r);
}
BENCHMARK(BM_HybridScatter)->ArgsProduct({{256, 1024}, {0, 1}})->Unit(benchmark::kMillisecond);

// The hybrid with its eye pass: what a frame pays when the camera moves.
void BM_HybridScatterWithEyePass(benchmark::State& state) {
  const BenchScene& s = scene(int(state.range(0)));
  ScatterResult r;
  for (auto _ : state) {
    const ShadowVolumeBuffers b = rasterize_shadow_volumes({&s.volume, 1}, s.view, s.depth);
    r = scatter_hybrid(s.view, s.depth, b, s.shadow, AirlightTable::shared(), s.medium, s.light, settings_of(state));
  }
  report(state, r);
}
BENCHMARK(BM_HybridScatterWithEyePass)->ArgsProduct({{256, 1024}, {0, 1}})->Unit(benchmark::kMillisecond);

void BM_BruteScatter(benchmark::State& state) {
  const BenchScene& s = scene(int(state.range(0)));
  ScatterResult r;
  for (auto _ : state)
    r = scatter_brute(s.view, s.depth, s.shadow, AirlightTable::shared(), s.medium, s.light, settings_of(state));
  report(state, r);
}
BENCHMARK(BM_BruteScatter)->ArgsProduct({{256, 1024}, {0, 1}})->Unit(benchmark::kMillisecond);

void BM_UnshadowedScatter(benchmark::State& state) {
  const BenchScene& s = scene(int(state.range(0)));
  for (auto _ : state)
    benchmark::DoNotOptimize(
        scatter_unshadowed(s.view, s.depth, AirlightTable::shared(), s.medium, s.light, settings_of(state))
            .r.data.data());
}
BENCHMARK(BM_UnshadowedScatter)->ArgsProduct({{256, 1024}, {0, 1}})->Unit(benchmark::kMillisecond);

void BM_TexturedSpotModel(benchmark::State& state) {
  const BenchScene& s = scene(512);
  SpotLight spot;
  spot.position = s.light.position;
  spot.direction = normalize(Vec3(0, 1.5f, 0) - spot.position);
  spot.up = normalize(cross(spot.direction, Vec3(1, 0, 0)));
  spot.cos_outer = std::cos(radians(35.0f));
  spot.cos_inner = std::cos(radians(28.0f));
  spot.intensity = RGB(20.0f);
  static const ShadowMap shadow = [&] {
    RasterScene raster;
    const Vec3 up{0, 1, 0};
    raster.add_triangle({-20, 0, -20}, {-20, 0, 20}, {20, 0, 20}, up, up, up, 0);
    raster.add_triangle({-20, 0, -20}, {20, 0, 20}, {20, 0, -20}, up, up, up, 0);
    const TriangleMesh occluder = testing::sphere_mesh({0, 1.5f, 0}, 1.0f, 4);
    const auto& p = occluder.positions;
    for (size_t i = 0; i + 2 < p.size(); i += 3) raster.add_triangle(p[i], p[i + 1], p[i + 2], up, up, up, 0);
    return *render_shadow_map(raster, ShadedLight{spot}, 1024, raster.bounds());
  }();
  const ScatteringMedium medium = state.range(1) ? ScatteringMedium{RGB(0.06f, 0.1f, 0.16f), RGB(0.1f, 0.15f, 0.22f)}
                                                 : ScatteringMedium{RGB(0.1f), RGB(0.15f)};
  TexturedSpotSettings settings;
  settings.model = state.range(0) ? SpotScatterModel::kHoffmanPreetham : SpotScatterModel::kAirlight;
  ScatterResult r;
  for (auto _ : state) r = scatter_textured_spot(s.view, s.depth, &shadow, medium, spot, settings);
  report(state, r);
}
BENCHMARK(BM_TexturedSpotModel)->ArgsProduct({{0, 1}, {0, 1}})->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace caligo
