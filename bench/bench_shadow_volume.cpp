// Shadow volumes (issue 8): edge adjacency of an occluder (once per mesh), silhouette and
// extrusion (once per light move), and the eye pass into front/back distances (per frame)
// at 256^2 and 1024^2. The occluder is a subdivided icosphere of 81,920 triangles over a
// ground plane, lit from above and to the side. Run:
// build/release/bench/caligo_bench --benchmark_filter=ShadowVolume
#include <benchmark/benchmark.h>

#include "hybrid/shadow_volume.h"
#include "hybrid/shadow_volume_testing.h"
#include "realtime/scene_buffers.h"

namespace caligo {
namespace {

constexpr Vec3 kLight{2.0f, 6.0f, 1.0f};

const TriangleMesh& occluder() {
  static const TriangleMesh mesh = testing::sphere_mesh({0, 1.5f, 0}, 1.0f, 6);  // 81,920 triangles
  return mesh;
}

void BM_ShadowVolumeEdges(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(MeshEdges(occluder()).edges().size());
  state.counters["triangles"] = double(occluder().triangle_count());
}
BENCHMARK(BM_ShadowVolumeEdges)->Unit(benchmark::kMillisecond);

void BM_ShadowVolumeBuild(benchmark::State& state) {
  const MeshEdges edges(occluder());
  size_t sides = 0;
  for (auto _ : state) sides = build_shadow_volume(edges, kLight, 40.0f).side_triangles;
  state.counters["side_triangles"] = double(sides);
}
BENCHMARK(BM_ShadowVolumeBuild)->Unit(benchmark::kMillisecond);

void BM_ShadowVolumeEyePass(benchmark::State& state) {
  const int res = int(state.range(0));
  const ShadowVolume volume = build_shadow_volume(MeshEdges(occluder()), kLight, 40.0f);
  RasterScene scene;
  const Vec3 up{0, 1, 0};
  scene.add_triangle({-20, 0, -20}, {-20, 0, 20}, {20, 0, 20}, up, up, up, 0);
  scene.add_triangle({-20, 0, -20}, {20, 0, 20}, {20, 0, -20}, up, up, up, 0);
  const auto& p = occluder().positions;
  for (size_t i = 0; i + 2 < p.size(); i += 3) scene.add_triangle(p[i], p[i + 1], p[i + 2], up, up, up, 0);
  const View view =
      View::perspective_view({0, 3, 8}, normalize(Vec3(0, -2.2f, -8)), up, radians(50.0f), {res, res});
  const Plane depth = rasterize_depth(scene, view);
  ShadowVolumeBuffers b;
  for (auto _ : state) b = rasterize_shadow_volumes({&volume, 1}, view, depth);
  int covered = 0;  // counted outside the timed loop
  for (int y = 0; y < res; ++y)
    for (int x = 0; x < res; ++x) covered += b.covered(x, y);
  state.counters["covered_pixels"] = covered;
}
BENCHMARK(BM_ShadowVolumeEyePass)->Arg(256)->Arg(1024)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace caligo
