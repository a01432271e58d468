// Test-only helpers: grids built in code (NanoVDB's builder) and placed as volume primitives.
#pragma once

#include <memory>

#include <nanovdb/util/GridBuilder.h>

#include "grids/volume_grid_build.h"
#include "volumes/volume.h"

namespace caligo::testing {

// A float grid named "density" with voxel centres at origin + voxel * (i, j, k).
template <typename Fn>
std::shared_ptr<const VolumeGrid> make_grid(Fn&& density, int n, float voxel, Vec3 origin) {
  nanovdb::GridBuilder<float> builder(0.0f);
  builder([&](const nanovdb::Coord& ijk) { return density(ijk[0], ijk[1], ijk[2]); },
          nanovdb::CoordBBox(nanovdb::Coord(0), nanovdb::Coord(n - 1)));
  NanoGrids grids{builder.getHandle<>(voxel, nanovdb::Vec3d(origin.x, origin.y, origin.z), "density"), {}, {}, {}};
  return make_volume_grid(std::move(grids), {"test", ""});
}

inline VolumePrimitive grid_primitive(std::shared_ptr<const VolumeGrid> grid, RGB sigma_a, RGB sigma_s,
                               GridFilter filter = GridFilter::kTrilinear) {
  const Bounds3 b = grid->world_bounds();
  VolumePrimitive v{BoxVolumeShape{Transform(), b.lo, b.hi}, {sigma_a, sigma_s}};
  v.shader.field = GridDensity{std::move(grid), Transform(), filter};
  return v;
}

}  // namespace caligo::testing
