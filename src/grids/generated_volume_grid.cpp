#include "grids/generated_volume_grid.h"

#include <map>
#include <mutex>
#include <tuple>

#include "grids/grid_io_internal.h"
#include "grids/volume_grid_build.h"

namespace caligo {

std::shared_ptr<const VolumeGrid> generated_volume_grid(const GenerateSettings& settings) {
  static std::mutex mutex;
  static std::map<std::tuple<int, int, uint64_t>, std::shared_ptr<const VolumeGrid>> cache;
  const auto key = std::make_tuple(int(settings.kind), settings.resolution, settings.seed);
  const std::lock_guard lock(mutex);
  if (const auto it = cache.find(key); it != cache.end()) return it->second;
  NanoGrids grids;
  bool have_density = false;
  for (const SparseFloatGrid& g : generate_grids(settings)) {
    NanoGridHandle handle = sparse_to_nanovdb(g);
    if (g.name == "density") {
      grids.density = std::move(handle);
      have_density = true;
    } else if (g.name == "temperature") {
      grids.temperature = std::move(handle);
    } else if (g.name == "flame") {
      grids.flame = std::move(handle);
    }
  }
  if (!have_density) throw std::logic_error("generated_volume_grid: the generator made no density grid");
  auto grid = make_volume_grid(std::move(grids), {"generated volume", ""});
  cache.emplace(key, grid);
  return grid;
}

}  // namespace caligo
