// Real-time scene buffers: the tiled SIMD rasteriser against Embree primary rays at
// 1920x1080, shadow-map rendering at 1024^2, and surface shading. The scene is a room
// corner with the Wuson mesh from Debian's assimp-testmodels (3,732 triangles; replaced by
// a second sphere when the package is missing), a sphere (4,032 triangles once
// tessellated) and a box. Run: build/release/bench/caligo_bench --benchmark_filter=Realtime
#include <benchmark/benchmark.h>

#include <filesystem>
#include <memory>

#include "realtime/scene_buffers.h"
#include "realtime/shadow_map.h"
#include "realtime/surface_shading.h"
#include "scene/scene.h"

namespace caligo {
namespace {

constexpr const char* kMesh = "/usr/share/assimp/models/OBJ/WusonOBJ.obj";
constexpr Vec2i kFullHd{1920, 1080};

struct RasterBench {
  std::unique_ptr<Scene> scene;
  RasterScene raster;
  View view;
};

SceneDesc bench_desc() {
  SceneDesc desc;
  desc.file = "bench";
  desc.camera.position = {0.4f, 1.3f, 4.2f};
  desc.camera.look_at = {0.0f, 0.7f, 0.0f};
  desc.camera.fov_degrees = 50.0f;
  desc.materials.push_back({"grey", DiffuseBsdf{RGB(0.6f)}, {}, false});
  desc.shapes.push_back({RectangleShape{{-6, 0, 6}, {12, 0, 0}, {0, 0, -12}}, {}, 0});
  desc.shapes.push_back({BoxShape{{-6, 0, -3}, {6, 4, -2.8f}}, {}, 0});
  desc.shapes.push_back({BoxShape{{-2.4f, 0, -1.5f}, {-1.4f, 1.0f, -0.5f}}, {}, 0});
  desc.shapes.push_back({SphereShape{{1.6f, 0.6f, -0.4f}, 0.6f}, {}, 0});
  if (std::filesystem::exists(kMesh))
    desc.shapes.push_back({MeshFileShape{kMesh, true}, Transform::translate({0, 0, 0.3f}), 0});
  else
    desc.shapes.push_back({SphereShape{{0, 0.7f, 0.3f}, 0.7f}, {}, 0});
  desc.lights.push_back(PointLight{{0.5f, 2.5f, 1.0f}, RGB(8.0f)});
  SpotLight spot;
  spot.position = {-1.5f, 3.0f, 2.0f};
  spot.direction = normalize(Vec3{0.4f, -1.0f, -0.6f});
  spot.up = normalize(cross(cross(spot.direction, Vec3{0, 0, 1}), spot.direction));
  spot.cos_outer = std::cos(0.6f);
  spot.cos_inner = std::cos(0.45f);
  spot.intensity = RGB(20.0f);
  desc.lights.push_back(spot);
  desc.lights.push_back(DirectionalLight{normalize(Vec3{0.3f, -1.0f, -0.4f}), RGB(1.5f)});
  return desc;
}

const RasterBench& bench_scene() {
  static const RasterBench b = [] {
    RasterBench r;
    r.scene = Scene::build(bench_desc());
    r.raster = RasterScene::build(*r.scene);
    r.view = View::from_camera(r.scene->camera(kFullHd), kFullHd);
    return r;
  }();
  return b;
}

// Arg: 1 SIMD, 0 scalar. The G-buffer is reused across frames, as the pipeline can.
void BM_RealtimeGBufferRaster(benchmark::State& state) {
  const RasterBench& b = bench_scene();
  GBuffer g;
  for (auto _ : state) {
    rasterize_gbuffer(b.raster, b.view, g, state.range(0) != 0);
    benchmark::DoNotOptimize(g.depth.data.data());
  }
  state.counters["triangles"] = double(b.raster.triangle_count());
}
BENCHMARK(BM_RealtimeGBufferRaster)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

// A fresh G-buffer per frame (allocation and page faults of ~44 MB included).
void BM_RealtimeGBufferRasterAllocating(benchmark::State& state) {
  const RasterBench& b = bench_scene();
  for (auto _ : state) benchmark::DoNotOptimize(rasterize_gbuffer(b.raster, b.view));
}
BENCHMARK(BM_RealtimeGBufferRasterAllocating)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_RealtimeGBufferEmbree(benchmark::State& state) {
  const RasterBench& b = bench_scene();
  for (auto _ : state) benchmark::DoNotOptimize(trace_gbuffer(*b.scene, b.view));
}
BENCHMARK(BM_RealtimeGBufferEmbree)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_RealtimeDepthRaster(benchmark::State& state) {
  const RasterBench& b = bench_scene();
  for (auto _ : state) benchmark::DoNotOptimize(rasterize_depth(b.raster, b.view));
}
BENCHMARK(BM_RealtimeDepthRaster)->Unit(benchmark::kMillisecond)->UseRealTime();

// Arg: light index (0 point = 6-face cube, 1 spot, 2 directional), each 1024^2 per face.
void BM_RealtimeShadowMap(benchmark::State& state) {
  const RasterBench& b = bench_scene();
  const ShadedLight light = *shaded_light(b.scene->lights()[size_t(state.range(0))]);
  for (auto _ : state)
    benchmark::DoNotOptimize(render_shadow_map(b.raster, light, 1024, b.scene->surfaces().bounds()));
}
BENCHMARK(BM_RealtimeShadowMap)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// The three lights, all shadowed, over the 1920x1080 G-buffer (no media).
void BM_RealtimeShadeSurfaces(benchmark::State& state) {
  const RasterBench& b = bench_scene();
  const GBuffer g = rasterize_gbuffer(b.raster, b.view);
  std::vector<std::optional<ShadowMap>> maps;
  std::vector<FrameLight> lights;
  for (const Light& l : b.scene->lights())
    maps.push_back(render_shadow_map(b.raster, *shaded_light(l), 1024, b.scene->surfaces().bounds()));
  for (size_t i = 0; i < maps.size(); ++i)
    lights.push_back({*shaded_light(b.scene->lights()[i]), {}, maps[i] ? &*maps[i] : nullptr, i});
  for (auto _ : state) benchmark::DoNotOptimize(shade_surfaces(g, b.view, *b.scene, lights));
}
BENCHMARK(BM_RealtimeShadeSurfaces)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace caligo
