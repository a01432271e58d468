// The real-time frame passes at the budget sizes (1920x1080 output, quarter-
// resolution accumulation 480x270, 16 samples): accumulation of one spot light in a fog
// box (SIMD and scalar), the seven-light mix of the `arena` budget, gather at 480x270,
// nearest-depth upsampling to 1920x1080 and temporal reprojection at 1920x1080. Shadow maps
// are left out (their lookups are timed with the shadow-map pass). Synthetic depth: a
// floor and a wall 30 m away, sky above.
#include <benchmark/benchmark.h>

#include <cmath>

#include "core/rng.h"
#include "realtime/froxel_fog.h"
#include "realtime/passes.h"
#include "realtime/scene_buffers.h"
#include "volumes/volume_scene.h"

namespace caligo {
namespace {

constexpr Vec2i kFull{1920, 1080};
constexpr Vec2i kLow{480, 270};

View camera_view(Vec2i res, Vec3 eye = {0.0f, 2.0f, 0.0f}) {
  return View::perspective_view(eye, normalize(Vec3(0.0f, -0.1f, -1.0f)), {0, 1, 0}, radians(60.0f), res);
}

// Linear depth of a floor (y = 0) and a wall (z = -30), sky elsewhere.
Plane scene_depth(const View& view) {
  Plane d(view.resolution.x, view.resolution.y, kSkyDepth);
  for (int y = 0; y < view.resolution.y; ++y)
    for (int x = 0; x < view.resolution.x; ++x) {
      const Ray r = view.ray({x + 0.5f, y + 0.5f});
      float t = kInfinity;
      if (r.direction.y < 0.0f) t = std::min(t, -r.origin.y / r.direction.y);
      if (r.direction.z < 0.0f) t = std::min(t, (-30.0f - r.origin.z) / r.direction.z);
      if (t < kInfinity) d.at(x, y) = t * view.depth_per_t(r.direction);
    }
  return d;
}

VolumeScene haze(bool with_noise_puff) {
  std::vector<VolumePrimitive> prims;
  VolumePrimitive box;
  box.shape = BoxVolumeShape{Transform(), {-25, -1, -35}, {25, 12, 5}};
  box.shader.sigma_a = RGB(0.005f);
  box.shader.sigma_s = RGB(0.04f);
  box.shader.phase = HenyeyGreensteinPhase{0.4f};
  prims.push_back(box);
  if (with_noise_puff) {
    VolumePrimitive puff = box;
    puff.shape = BoxVolumeShape{Transform(), {2, 0, -16}, {8, 5, -10}};
    puff.shader.sigma_s = RGB(0.2f);
    puff.shader.noise = NoiseModulation{0.8f, 0.7f, {}, {}};
    prims.push_back(puff);
  }
  return VolumeScene(std::move(prims));
}

SpotLight spot(Vec3 pos, Vec3 dir, float outer_deg, RGB intensity) {
  SpotLight s;
  s.position = pos;
  s.direction = normalize(dir);
  s.cos_outer = std::cos(radians(outer_deg));
  s.cos_inner = std::cos(radians(outer_deg * 0.7f));
  s.intensity = intensity;
  s.range = 14.0f;
  return s;
}

// The arena's mix: 4 spots, a point light in the noise puff, a box light and the sun.
std::vector<FrameLight> seven_lights() {
  std::vector<Light> lights = {spot({0, 7, -12}, {0, -1, 0.1f}, 30.0f, RGB(200.0f)),
                               spot({-8, 6, -18}, {0.3f, -1, 0}, 25.0f, RGB(150.0f, 120.0f, 90.0f)),
                               spot({8, 6, -20}, {-0.3f, -1, 0.2f}, 20.0f, RGB(100.0f, 150.0f, 200.0f)),
                               spot({-4, 5, -8}, {0.2f, -1, -0.3f}, 35.0f, RGB(80.0f)),
                               PointLight{{5, 2.5f, -13}, RGB(60.0f, 40.0f, 20.0f), 8.0f, {}}};
  BoxLight b;
  b.position = {-3, 10, -25};
  b.direction = {0, -1, 0};
  b.up = {0, 0, 1};
  b.half_width = 2.0f;
  b.half_height = 1.0f;
  b.range = 10.0f;
  b.irradiance = RGB(3.0f);
  lights.push_back(b);
  lights.push_back(DirectionalLight{normalize(Vec3(0.3f, -1.0f, -0.4f)), RGB(0.8f)});
  std::vector<FrameLight> out;
  for (Light& l : lights) out.push_back(FrameLight{*shaded_light(l), LightOptions{}, nullptr});
  return out;
}

void BM_AccumulateSpot(benchmark::State& state) {
  const View view = camera_view(kLow);
  const Plane depth = scene_depth(view);
  const VolumeScene volumes = haze(false);
  const FrameLight light{spot({0, 7, -12}, {0, -1, 0.1f}, 30.0f, RGB(200.0f)), LightOptions{}, nullptr};
  AccumulationSettings s;
  s.simd = state.range(0) != 0;
  ColorPlanes accum(kLow.x, kLow.y);
  for (auto _ : state) {
    accumulate_light(light, volumes, view, depth, s, accum);
    benchmark::DoNotOptimize(accum.r.data.data());
  }
  state.SetLabel(s.simd ? "simd" : "scalar");
}
BENCHMARK(BM_AccumulateSpot)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);

void BM_AccumulateSevenLights(benchmark::State& state) {
  const View view = camera_view(kLow);
  const Plane depth = scene_depth(view);
  const VolumeScene volumes = haze(true);
  const std::vector<FrameLight> lights = seven_lights();
  AccumulationSettings s;
  s.simd = state.range(0) != 0;
  ColorPlanes accum(kLow.x, kLow.y);
  for (auto _ : state) {
    for (const FrameLight& l : lights) accumulate_light(l, volumes, view, depth, s, accum);
    benchmark::DoNotOptimize(accum.r.data.data());
  }
  state.SetLabel(s.simd ? "simd" : "scalar");
}
BENCHMARK(BM_AccumulateSevenLights)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);

ColorPlanes noise_planes(Vec2i res) {
  Pcg32 rng(1, 1);
  ColorPlanes c(res.x, res.y);
  for (Plane* p : {&c.r, &c.g, &c.b})
    for (float& v : p->data) v = rng.next_float();
  return c;
}

void BM_Gather(benchmark::State& state) {
  const Plane depth = scene_depth(camera_view(kLow));
  const ColorPlanes in = noise_planes(kLow);
  const bool simd = state.range(0) != 0;
  for (auto _ : state) benchmark::DoNotOptimize(bilateral_gather(in, depth, 7, 1000.0f, simd));
  state.SetLabel(simd ? "simd" : "scalar");
}
BENCHMARK(BM_Gather)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);

// The low-resolution depth at quarter resolution: point-sampled centres (0) or min/max (1).
void BM_DownsampleDepth(benchmark::State& state) {
  const Plane full = scene_depth(camera_view(kFull));
  const auto mode = state.range(0) != 0 ? LowResolutionDepth::min_max : LowResolutionDepth::centre;
  for (auto _ : state) benchmark::DoNotOptimize(downsample_depth(full, 4, mode).data.data());
  state.SetLabel(state.range(0) != 0 ? "min_max" : "centre");
}
BENCHMARK(BM_DownsampleDepth)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);

void BM_Upsample(benchmark::State& state) {
  const Plane full = scene_depth(camera_view(kFull));
  const Plane low_depth = downsample_depth(full, 4);
  const ColorPlanes low = noise_planes(kLow);
  const bool simd = state.range(0) != 0;
  ColorPlanes out;  // reused across frames, as the pipeline does
  for (auto _ : state) {
    upsample_nearest_depth(low, low_depth, full, out, 0.05f, simd);
    benchmark::DoNotOptimize(out.r.data.data());
  }
  state.SetLabel(simd ? "simd" : "scalar");
}
BENCHMARK(BM_Upsample)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);

// The froxel grid's per-pixel lookup at 1080p from a 160 x 90 x 64 grid: four 8-float loads a
// pixel (1) against 24 AVX2 gathers per 8 pixels (0, the former lookup).
void BM_FroxelLookup(benchmark::State& state) {
  const Plane full = scene_depth(camera_view(kFull));
  FroxelGrid grid;
  grid.width = 160, grid.height = 90, grid.slices = 64, grid.near = 0.2f, grid.far = 60.0f;
  Pcg32 rng(2, 3);
  std::vector<RGB> integrated(grid.columns() * size_t(grid.slices + 1));
  for (RGB& v : integrated) v = RGB(rng.next_float(), rng.next_float(), rng.next_float());
  const auto method = state.range(0) != 0 ? FroxelLookup::loads : FroxelLookup::gathers;
  ColorPlanes out;
  for (auto _ : state) {
    lookup_froxels(grid, integrated, full, out, method);
    benchmark::DoNotOptimize(out.r.data.data());
  }
  state.SetLabel(state.range(0) != 0 ? "loads" : "gathers");
}
BENCHMARK(BM_FroxelLookup)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);

void BM_Temporal(benchmark::State& state) {
  const View now = camera_view(kFull, {0.05f, 2.0f, 0.0f}), before = camera_view(kFull);
  const Plane depth = scene_depth(now), history_depth = scene_depth(before);
  const ColorPlanes current = noise_planes(kFull), history = noise_planes(kFull);
  const bool simd = state.range(0) != 0;
  ColorPlanes out;
  for (auto _ : state) {
    temporal_reproject(current, depth, now, history, history_depth, before, 0.1f, out, simd);
    benchmark::DoNotOptimize(out.r.data.data());
  }
  state.SetLabel(simd ? "simd" : "scalar");
}
BENCHMARK(BM_Temporal)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace caligo
