// Grid files: generating the procedural volumes, and loading a generated cloud from OpenVDB
// (.vdb: decompress, then convert to NanoVDB) and NanoVDB (.nvdb: read, validate) files, to
// NanoVDB handles and to a full VolumeGrid. Counters: file bytes, NanoVDB bytes, VolumeGrid bytes.
#include <benchmark/benchmark.h>

#include <unistd.h>

#include <filesystem>

#include "grids/grid_generate.h"
#include "grids/grid_io.h"
#include "grids/grid_io_internal.h"

namespace caligo {
namespace {

namespace fs = std::filesystem;

constexpr int kResolution = 128;

// The cloud written once per process in both formats; returns the path for `extension`.
std::string cloud_file(const std::string& extension) {
  static const fs::path dir = fs::temp_directory_path() / ("caligo-bench-grid-" + std::to_string(::getpid()));
  static const bool written = [] {
    fs::create_directories(dir);
    const auto grids = generate_grids({GeneratedVolume::kCloud, kResolution, 1});
    write_grid_file((dir / "cloud.vdb").string(), grids);
    write_grid_file((dir / "cloud.nvdb").string(), grids);
    std::atexit([] { fs::remove_all(dir); });
    return true;
  }();
  (void)written;
  return (dir / ("cloud" + extension)).string();
}

void BM_GenerateGrids(benchmark::State& state) {
  const auto kind = GeneratedVolume(state.range(0));
  uint64_t active = 0;
  for (auto _ : state) {
    const auto grids = generate_grids({kind, int(state.range(1)), 1});
    active = grids[0].active_voxels();
    benchmark::DoNotOptimize(active);
  }
  state.counters["density_active_voxels"] = double(active);
}
BENCHMARK(BM_GenerateGrids)
    ->ArgsProduct({{int(GeneratedVolume::kCloud), int(GeneratedVolume::kSmoke), int(GeneratedVolume::kFire)},
                   {128}})
    ->ArgNames({"kind", "res"})
    ->Unit(benchmark::kMillisecond);

void BM_ReadGridFile(benchmark::State& state, const std::string& extension) {
  const std::string path = cloud_file(extension);
  uint64_t nano_bytes = 0;
  for (auto _ : state) {
    const NanoGrids grids = read_grid_channels(path, GridChannels{}, {});
    nano_bytes = grids.density.size();
  }
  state.counters["file_bytes"] = double(fs::file_size(path));
  state.counters["nanovdb_bytes"] = double(nano_bytes);
}
BENCHMARK_CAPTURE(BM_ReadGridFile, vdb, std::string(".vdb"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ReadGridFile, nvdb, std::string(".nvdb"))->Unit(benchmark::kMillisecond);

void BM_LoadVolumeGrid(benchmark::State& state, const std::string& extension) {
  const std::string path = cloud_file(extension);
  size_t memory = 0, nano = 0;
  for (auto _ : state) {
    const auto grid = load_grid_file(path, GridChannels{}, {});
    memory = grid->memory_bytes();
    nano = grid->nanovdb_bytes();
  }
  state.counters["volume_grid_bytes"] = double(memory);
  state.counters["memory_over_nanovdb"] = double(memory) / double(nano);
}
BENCHMARK_CAPTURE(BM_LoadVolumeGrid, vdb, std::string(".vdb"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_LoadVolumeGrid, nvdb, std::string(".nvdb"))->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace caligo
