// The sparse-grid core on a 160^3 cloud-like grid (a cluster of noisy spheres built with
// nanovdb::GridBuilder): trilinear lookups per second along rays (coherent: consecutive points
// share leaves and the accessor's cached path) and at random points, block-DDA interval lists
// per second, and the memory of the loaded grid against its NanoVDB form.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include <nanovdb/util/GridBuilder.h>

#include "core/rng.h"
#include "grids/grid_accessor_cache.h"
#include "grids/volume_grid.h"
#include "grids/volume_grid_build.h"

namespace caligo {
namespace {

float hash01(int32_t i, int32_t j, int32_t k) {
  uint32_t h = 0x9E3779B9u;
  for (int32_t v : {i, j, k}) {
    h ^= uint32_t(v) + 0x7F4A7C15u + (h << 6) + (h >> 2);
    h *= 0x85EBCA6Bu;
    h ^= h >> 13;
  }
  return float(h >> 8) * (1.0f / 16777216.0f);
}

// Value noise: trilinear interpolation of a hashed lattice of spacing 8 voxels.
float value_noise(float x, float y, float z) {
  const float fx = std::floor(x), fy = std::floor(y), fz = std::floor(z);
  const int i = int(fx), j = int(fy), k = int(fz);
  const float u = x - fx, v = y - fy, w = z - fz;
  float r = 0.0f;
  for (int c = 0; c < 8; ++c) {
    const int dx = c & 1, dy = (c >> 1) & 1, dz = c >> 2;
    r += (dx ? u : 1 - u) * (dy ? v : 1 - v) * (dz ? w : 1 - w) * hash01(i + dx, j + dy, k + dz);
  }
  return r;
}

const VolumeGrid& cloud() {
  static const std::shared_ptr<const VolumeGrid> grid = [] {
    nanovdb::GridBuilder<float> builder(0.0f);
    auto acc = builder.getAccessor();
    const float centres[4][4] = {{0, 0, 0, 55}, {40, 10, 0, 35}, {-35, 5, 20, 35}, {5, 30, -30, 30}};
    for (int i = -80; i < 80; ++i)
      for (int j = -80; j < 80; ++j)
        for (int k = -80; k < 80; ++k) {
          float shape = 0.0f;
          for (const auto& c : centres) {
            const float d =
                std::sqrt((i - c[0]) * (i - c[0]) + (j - c[1]) * (j - c[1]) + (k - c[2]) * (k - c[2]));
            shape = std::max(shape, 1.0f - d / c[3]);
          }
          const float v = shape + 0.35f * (value_noise(i / 8.0f, j / 8.0f, k / 8.0f) - 0.5f);
          if (v > 0.0f) acc.setValue(nanovdb::Coord(i, j, k), std::min(1.0f, 3.0f * v));
        }
    return make_volume_grid({builder.getHandle<>(0.01)}, {"bench cloud", ""});
  }();
  return *grid;
}

std::vector<Ray> random_rays(const VolumeGrid& grid, int n) {
  Pcg32 rng(17, 5);
  const Bounds3 b = grid.world_bounds();
  const float r = 0.5f * length(b.diagonal());
  std::vector<Ray> rays;
  for (int i = 0; i < n; ++i) {
    const float z = 1 - 2 * rng.next_float(), phi = 2 * kPi * rng.next_float();
    const Vec3 d(std::sqrt(1 - z * z) * std::cos(phi), std::sqrt(1 - z * z) * std::sin(phi), z);
    const Vec3 target =
        b.lo +
        mul(b.diagonal(), Vec3(rng.next_float(), rng.next_float(), rng.next_float()) * 0.6f + Vec3(0.2f));
    rays.push_back({target - d * (2 * r), d});
  }
  return rays;
}

void BM_GridLookupCoherent(benchmark::State& state) {
  const VolumeGrid& grid = cloud();
  const auto filter = state.range(0) ? GridFilter::kTrilinear : GridFilter::kNearest;
  const std::vector<Ray> rays = random_rays(grid, 256);
  GridAccessorCache cache;
  const float step = 0.5f * grid.voxel_size();
  const float r = length(grid.world_bounds().diagonal());
  int64_t lookups = 0;
  size_t next = 0;
  float sum = 0.0f;
  for (auto _ : state) {
    const Ray& ray = rays[next++ % rays.size()];
    for (float t = 0.5f * r; t < 1.5f * r; t += step) sum += grid.density(ray.at(t), filter, cache);
    lookups += int64_t(r / step);
  }
  benchmark::DoNotOptimize(sum);
  state.SetItemsProcessed(lookups);
  state.SetLabel(filter == GridFilter::kTrilinear ? "trilinear" : "nearest");
}
BENCHMARK(BM_GridLookupCoherent)->Arg(1)->Arg(0);

void BM_GridLookupRandom(benchmark::State& state) {
  const VolumeGrid& grid = cloud();
  const Bounds3 b = grid.world_bounds();
  Pcg32 rng(3, 3);
  std::vector<Vec3> points(1 << 16);
  for (Vec3& p : points)
    p = b.lo + mul(b.diagonal(), Vec3(rng.next_float(), rng.next_float(), rng.next_float()));
  GridAccessorCache cache;
  size_t next = 0;
  float sum = 0.0f;
  for (auto _ : state) {
    for (int i = 0; i < 256; ++i)
      sum += grid.density(points[next++ & (points.size() - 1)], GridFilter::kTrilinear, cache);
  }
  benchmark::DoNotOptimize(sum);
  state.SetItemsProcessed(int64_t(state.iterations()) * 256);
}
BENCHMARK(BM_GridLookupRandom);

void BM_GridIntervals(benchmark::State& state) {
  const VolumeGrid& grid = cloud();
  const std::vector<Ray> rays = random_rays(grid, 4096);
  const float tolerance = state.range(0) / 100.0f;
  std::vector<GridInterval> out;
  size_t next = 0, intervals = 0;
  for (auto _ : state) {
    out.clear();
    grid.intervals(rays[next++ % rays.size()], 0.0f, kInfinity, out, tolerance);
    intervals += out.size();
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(int64_t(state.iterations()));  // rays
  state.counters["intervals_per_ray"] = double(intervals) / double(state.iterations());
}
BENCHMARK(BM_GridIntervals)->Arg(0)->Arg(25)->Arg(100);

void BM_GridMemory(benchmark::State& state) {
  const VolumeGrid& grid = cloud();
  for (auto _ : state) benchmark::DoNotOptimize(grid.memory_bytes());
  const GridStatistics s = grid.statistics();
  state.counters["memory_bytes"] = double(grid.memory_bytes());
  state.counters["nanovdb_bytes"] = double(grid.nanovdb_bytes());
  state.counters["ratio"] = double(grid.memory_bytes()) / double(grid.nanovdb_bytes());
  state.counters["active_voxels"] = double(s.active_voxels);
  state.counters["blocks"] = double(s.blocks);
  state.counters["constant_blocks"] = double(s.constant_blocks);
}
BENCHMARK(BM_GridMemory);

}  // namespace
}  // namespace caligo
