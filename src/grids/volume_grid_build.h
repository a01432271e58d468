// Building a VolumeGrid from NanoVDB grids (includes NanoVDB: use only where grids are made,
// i.e. grid files, the generator and tests).
#pragma once

#include <memory>
#include <optional>

#include <nanovdb/util/GridHandle.h>
#include <nanovdb/util/HostBuffer.h>

#include "core/error.h"
#include "grids/volume_grid.h"

namespace caligo {

using NanoGridHandle = nanovdb::GridHandle<nanovdb::HostBuffer>;

struct NanoGrids {
  NanoGridHandle density;                     // a float grid (required)
  std::optional<NanoGridHandle> temperature;  // float
  std::optional<NanoGridHandle> flame;        // float
  std::optional<NanoGridHandle> color;        // Vec3f ("Cd")
};

// Validates (grid types, non-finite or negative densities, absurd sizes) and builds the block
// structure. Errors are InputError at `where`.
std::shared_ptr<const VolumeGrid> make_volume_grid(NanoGrids grids, const SourceLocation& where);

}  // namespace caligo
