// Test-only helpers: small NanoVDB grids built voxel by voxel with nanovdb::GridBuilder.
#pragma once

#include <cmath>
#include <cstdint>
#include <string>

#include <nanovdb/util/GridBuilder.h>

#include "core/rng.h"
#include "grids/volume_grid_build.h"

namespace caligo::testing {

// fill(acc) sets voxels through acc.setValue(nanovdb::Coord, T).
template <class T, class Fill>
NanoGridHandle make_nano_grid(Fill&& fill, double voxel_size = 1.0,
                              nanovdb::Vec3d origin = nanovdb::Vec3d(0.0), T background = T(0),
                              const std::string& name = "grid") {
  nanovdb::GridBuilder<T> builder(background);
  auto acc = builder.getAccessor();
  fill(acc);
  return builder.template getHandle<>(voxel_size, origin, name);
}

// A deterministic hash-based value in [0, 1) for voxel (i, j, k) and a seed.
inline float hash01(int32_t i, int32_t j, int32_t k, uint32_t seed) {
  uint32_t h = seed * 0x9E3779B9u;
  for (int32_t v : {i, j, k}) {
    h ^= uint32_t(v) + 0x7F4A7C15u + (h << 6) + (h >> 2);
    h *= 0x85EBCA6Bu;
    h ^= h >> 13;
  }
  h *= 0xC2B2AE35u;
  h ^= h >> 16;
  return float(h >> 8) * (1.0f / 16777216.0f);
}

}  // namespace caligo::testing
