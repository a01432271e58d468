// make_volume_grid: validation of the NanoVDB grids, their statistics, and the block structure.
#include "grids/volume_grid_build.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <sstream>
#include <string>

#include "grids/grid_blocks_build.h"
#include "grids/grid_tree_walk.h"
#include "grids/volume_grid_data.h"

namespace caligo {
namespace {

using nanovdb::Coord;

std::string coord_string(const Coord& c) {
  return "(" + std::to_string(c[0]) + ", " + std::to_string(c[1]) + ", " + std::to_string(c[2]) + ")";
}

std::string value_string(float v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// A typed view of a handle's first grid, or an InputError naming the role and both types.
template <class T>
const nanovdb::NanoGrid<T>* typed_grid(const NanoGridHandle& handle, const char* role, const char* expected,
                                       const SourceLocation& where) {
  const nanovdb::GridMetaData* meta = handle.gridMetaData();
  if (handle.size() == 0 || !meta || !meta->isValid())
    throw InputError(where, std::string("grid '") + role + "' is empty or not a NanoVDB grid");
  const auto* grid = handle.grid<T>();
  if (!grid)
    throw InputError(where, std::string("grid '") + role + "' must be a " + expected + " grid, got " +
                                nanovdb::toStr(meta->gridType()));
  return grid;
}

// Checks every value a lookup can return (leaf values active or not, tiles, background) and
// gathers statistics of the active ones.
struct ScalarScan {
  const char* role;
  bool non_negative;
  const SourceLocation& where;
  uint64_t active = 0;
  float lo = 0.0f, hi = 0.0f;

  void check(float v, const Coord& at) const {
    if (!std::isfinite(v))
      throw InputError(where, std::string("grid '") + role + "' has a non-finite value " + value_string(v) +
                                  " at voxel " + coord_string(at));
    if (non_negative && v < 0.0f)
      throw InputError(where, std::string("grid '") + role + "' has a negative value " + value_string(v) +
                                  " at voxel " + coord_string(at) + " (densities must be >= 0)");
  }
  void count(float v, uint64_t voxels) {
    lo = active == 0 ? v : std::min(lo, v);
    hi = active == 0 ? v : std::max(hi, v);
    active += voxels;
  }

  void scan(const nanovdb::FloatGrid& grid) {
    const float background = grid.tree().root().background();
    check(background, Coord(0));
    if (background != 0.0f)
      throw InputError(where, std::string("grid '") + role + "' has background " + value_string(background) +
                                  " (it must be 0: a non-zero background fills all space)");
    walk_tree(
        grid,
        [&](const auto& leaf, Coord origin) {
          for (uint32_t n = 0; n < 512; ++n) {
            const float v = leaf.getValue(n);
            check(v, origin.offsetBy(int(n >> 6), int((n >> 3) & 7), int(n & 7)));
            if (leaf.isActive(n)) count(v, 1);
          }
        },
        [&](float v, bool active, Coord origin, uint32_t dim) {
          check(v, origin);
          if (active) count(v, uint64_t(dim) * dim * dim);
        });
  }
};

void check_colors(const nanovdb::Vec3fGrid& grid, const SourceLocation& where) {
  auto finite = [](const nanovdb::Vec3f& c) {
    return std::isfinite(c[0]) && std::isfinite(c[1]) && std::isfinite(c[2]);
  };
  auto fail = [&](const Coord& at) {
    throw InputError(where, "grid 'Cd' has a non-finite colour at voxel " + coord_string(at));
  };
  if (!finite(grid.tree().root().background())) fail(Coord(0));
  walk_tree(
      grid,
      [&](const auto& leaf, Coord origin) {
        for (uint32_t n = 0; n < 512; ++n)
          if (!finite(leaf.getValue(n))) fail(origin.offsetBy(int(n >> 6), int((n >> 3) & 7), int(n & 7)));
      },
      [&](const nanovdb::Vec3f& c, bool, Coord origin, uint32_t) {
        if (!finite(c)) fail(origin);
      });
}

bool same_index_space(const nanovdb::GridData& a, const nanovdb::GridData& b) {
  const nanovdb::Map &ma = a.mMap, &mb = b.mMap;
  double scale = 0.0;
  for (double v : ma.mMatD) scale = std::max(scale, std::abs(v));
  const double tolerance = 1e-5 * scale;
  for (int i = 0; i < 9; ++i)
    if (std::abs(ma.mMatD[i] - mb.mMatD[i]) > tolerance) return false;
  for (int i = 0; i < 3; ++i)
    if (std::abs(ma.mVecD[i] - mb.mVecD[i]) > tolerance) return false;
  return true;
}

void check_map(const nanovdb::GridData& grid, const char* role, const SourceLocation& where) {
  const nanovdb::Vec3d v = grid.mVoxelSize;
  bool ok = true;
  for (int a = 0; a < 3; ++a) ok = ok && std::isfinite(v[a]) && v[a] > 0.0;
  const nanovdb::Map& map = grid.mMap;
  for (float m : map.mMatF) ok = ok && std::isfinite(m);
  for (float m : map.mInvMatF) ok = ok && std::isfinite(m);
  for (float m : map.mVecF) ok = ok && std::isfinite(m);
  for (double m : map.mMatD) ok = ok && std::isfinite(m);
  for (double m : map.mInvMatD) ok = ok && std::isfinite(m);
  for (double m : map.mVecD) ok = ok && std::isfinite(m);
  // A file stores the map and its inverse, in double and float, separately: the bounds use the
  // double map, lookups and traversal the float inverse, so they must agree (M * M^-1 = I up to
  // rounding, which also rules out a singular M).
  for (int i = 0; ok && i < 3; ++i)
    for (int j = 0; ok && j < 3; ++j) {
      double product = 0.0, product_f = 0.0, magnitude = 0.0;
      for (int k = 0; k < 3; ++k) {
        product += map.mMatD[3 * i + k] * map.mInvMatD[3 * k + j];
        product_f += map.mMatD[3 * i + k] * double(map.mInvMatF[3 * k + j]);
        magnitude += std::abs(map.mMatD[3 * i + k] * map.mInvMatD[3 * k + j]);
      }
      const double identity = i == j ? 1.0 : 0.0, tolerance = 1e-5 * std::max(1.0, magnitude);
      ok = std::abs(product - identity) <= tolerance && std::abs(product_f - identity) <= tolerance;
    }
  for (int a = 0; ok && a < 3; ++a)
    ok = std::abs(double(map.mVecF[a]) - map.mVecD[a]) <= 1e-6 * std::max(1.0, std::abs(map.mVecD[a]));
  if (!ok)
    throw InputError(where, std::string("grid '") + role + "' has a degenerate or non-finite transform");
}

Bounds3 index_box_to_world(const nanovdb::GridData& grid, const GridBlocks& blocks) {
  Bounds3 bounds;
  if (blocks.empty()) return bounds;
  for (int corner = 0; corner < 8; ++corner) {
    nanovdb::Vec3d x;
    for (int a = 0; a < 3; ++a)
      x[a] = double((corner >> a) & 1 ? (blocks.block_hi[a] + 1) : blocks.block_lo[a]) * kBlockEdge;
    const nanovdb::Vec3d w = grid.applyMap(x);
    bounds.extend(Vec3(float(w[0]), float(w[1]), float(w[2])));
  }
  return bounds;
}

std::atomic<uint64_t> next_grid_id{1};

}  // namespace

std::shared_ptr<const VolumeGrid> make_volume_grid(NanoGrids grids, const SourceLocation& where) {
  auto data = std::make_unique<VolumeGridData>();
  data->density = typed_grid<float>(grids.density, "density", "float", where);
  if (grids.temperature)
    data->temperature = typed_grid<float>(*grids.temperature, "temperature", "float", where);
  if (grids.flame) data->flame = typed_grid<float>(*grids.flame, "flame", "float", where);
  if (grids.color) data->color = typed_grid<nanovdb::Vec3f>(*grids.color, "Cd", "vec3 float", where);

  const nanovdb::GridData& density = *data->density->data();
  check_map(density, "density", where);
  for (auto [grid, role] : {std::pair{data->temperature, "temperature"}, std::pair{data->flame, "flame"}}) {
    if (!grid) continue;
    check_map(*grid->data(), role, where);
    if (!same_index_space(density, *grid->data()))
      throw InputError(where,
                       std::string("grid '") + role +
                           "' has a different transform from 'density' (resample it onto the density grid)");
  }
  if (data->color) {
    check_map(*data->color->data(), "Cd", where);
    data->color_shares_index_space = same_index_space(density, *data->color->data());
    check_colors(*data->color, where);
  }

  ScalarScan density_scan{"density", true, where};
  density_scan.scan(*data->density);
  if (data->temperature) ScalarScan{"temperature", false, where}.scan(*data->temperature);
  if (data->flame) ScalarScan{"flame", false, where}.scan(*data->flame);

  BlockChannels channels{data->density, data->temperature, data->flame,
                         data->color_shares_index_space ? data->color : nullptr};
  data->blocks = build_grid_blocks(channels, where);
  if (data->color && !data->color_shares_index_space) {
    // The colour is read through its own map and may vary inside any block (it tints sigma_s,
    // hence the extinction): no block can promise constant coefficients.
    for (ParentCell& cell : data->blocks.parents) cell.constant_bits.fill(0);
    data->blocks.constant_blocks = 0;
  }
  if (data->blocks.empty())
    throw InputError(where, "grid 'density' is empty (no non-zero voxels, and no temperature or flame)");

  data->statistics = {density_scan.active, data->blocks.occupied_blocks, data->blocks.constant_blocks,
                      density_scan.lo, density_scan.hi};
  data->world_bounds = index_box_to_world(density, data->blocks);
  const nanovdb::Vec3d v = density.mVoxelSize;
  data->voxel_size = float(std::min(v[0], std::min(v[1], v[2])));
  data->id = next_grid_id.fetch_add(1);
  data->handles = std::move(grids);
  return std::make_shared<const VolumeGrid>(std::move(data));
}

}  // namespace caligo
