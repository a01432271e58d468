// The NanoVDB accessors of one grid set, held by a GridAccessorCache (one per thread).
#pragma once

#include <optional>

#include <nanovdb/NanoVDB.h>

#include "grids/volume_grid_data.h"

namespace caligo {

struct GridAccessors {
  using FloatAccessor = nanovdb::DefaultReadAccessor<float>;
  using ColorAccessor = nanovdb::DefaultReadAccessor<nanovdb::Vec3f>;

  explicit GridAccessors(const VolumeGridData& grid) : id(grid.id), density(grid.density->getAccessor()) {
    if (grid.temperature) temperature.emplace(grid.temperature->getAccessor());
    if (grid.flame) flame.emplace(grid.flame->getAccessor());
    if (grid.color) color.emplace(grid.color->getAccessor());
  }

  uint64_t id;
  FloatAccessor density;
  std::optional<FloatAccessor> temperature, flame;
  std::optional<ColorAccessor> color;
};

}  // namespace caligo
