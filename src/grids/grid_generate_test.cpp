// The procedural volumes: ranges, placement, determinism and the flat cloud base.
#include "grids/grid_generate.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "core/error.h"

namespace caligo {
namespace {

struct Range {
  float lo = kInfinity, hi = -kInfinity;
  uint64_t active = 0;
};

Range active_range(const SparseFloatGrid& g) {
  Range r;
  for (const SparseBlock& b : g.blocks)
    for (float v : b.values)
      if (v != 0.0f) {
        r.lo = std::min(r.lo, v);
        r.hi = std::max(r.hi, v);
        ++r.active;
      }
  return r;
}

// Calls f(world position, value) for every active voxel.
template <typename F>
void for_each_active(const SparseFloatGrid& g, F f) {
  for (const SparseBlock& b : g.blocks)
    for (int x = 0; x < kBlockDim; ++x)
      for (int y = 0; y < kBlockDim; ++y)
        for (int z = 0; z < kBlockDim; ++z) {
          const float v = b.values[size_t(block_offset(x, y, z))];
          if (v == 0.0f) continue;
          f(g.origin +
                g.voxel_size * Vec3(float(b.origin[0] + x), float(b.origin[1] + y), float(b.origin[2] + z)),
            v);
        }
}

bool identical(const std::vector<SparseFloatGrid>& a, const std::vector<SparseFloatGrid>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i].name != b[i].name || a[i].blocks.size() != b[i].blocks.size()) return false;
    for (size_t k = 0; k < a[i].blocks.size(); ++k)
      if (a[i].blocks[k].origin != b[i].blocks[k].origin || a[i].blocks[k].values != b[i].blocks[k].values)
        return false;
  }
  return true;
}

TEST(GridGenerate, EveryKindFillsItsBoxWithDensityInZeroOne) {
  for (GeneratedVolume kind : {GeneratedVolume::kCloud, GeneratedVolume::kSmoke, GeneratedVolume::kFire}) {
    const std::vector<SparseFloatGrid> grids = generate_grids({kind, 32, 5});
    ASSERT_FALSE(grids.empty());
    EXPECT_EQ(grids[0].name, "density");
    const Range r = active_range(grids[0]);
    EXPECT_GT(r.active, 1000u) << int(kind);
    EXPECT_GE(r.lo, 1e-3f);  // fainter voxels are left inactive
    EXPECT_LE(r.hi, 1.0f);
    EXPECT_GT(r.hi, 0.5f) << int(kind);
    // Voxel size = longest edge / resolution, and every active voxel centre inside the box.
    const Bounds3 box = generated_bounds(kind);
    EXPECT_FLOAT_EQ(grids[0].voxel_size, max_component(box.diagonal()) / 32.0f);
    for (const SparseFloatGrid& g : grids)
      for_each_active(g, [&](Vec3 p, float) { ASSERT_TRUE(box.contains(p)) << g.name; });
  }
}

TEST(GridGenerate, CloudIsDenseInsideWithAFlatBase) {
  const std::vector<SparseFloatGrid> grids = generate_grids({GeneratedVolume::kCloud, 48, 3});
  ASSERT_EQ(grids.size(), 1u);
  EXPECT_FLOAT_EQ(active_range(grids[0]).hi, 1.0f);
  float lowest = kInfinity;
  for_each_active(grids[0], [&](Vec3 p, float) { lowest = std::min(lowest, p.y); });
  // The base plane sits at 0.42 m and is not displaced.
  EXPECT_GE(lowest, 0.42f);
  EXPECT_LT(lowest, 0.42f + 2.0f * grids[0].voxel_size);
}

TEST(GridGenerate, FireHasKelvinTemperatureAndFlame) {
  const std::vector<SparseFloatGrid> grids = generate_grids({GeneratedVolume::kFire, 40, 9});
  ASSERT_EQ(grids.size(), 3u);
  EXPECT_EQ(grids[1].name, "temperature");
  EXPECT_EQ(grids[2].name, "flame");
  const Range t = active_range(grids[1]);
  EXPECT_GT(t.hi, 2000.0f);  // a hot core, in Kelvin
  EXPECT_LE(t.hi, 3000.0f);
  EXPECT_GE(t.lo, 300.0f);  // cooler voxels are left inactive
  const Range f = active_range(grids[2]);
  EXPECT_GT(f.hi, 0.5f);
  EXPECT_LE(f.hi, 1.0f);
  // The temperature is highest near the ball's centre (0, 1.35, 0).
  float hottest = 0.0f;
  Vec3 where;
  for_each_active(grids[1], [&](Vec3 p, float v) {
    if (v > hottest) hottest = v, where = p;
  });
  EXPECT_LT(distance(where, Vec3(0.0f, 1.35f, 0.0f)), 0.4f);
}

TEST(GridGenerate, DeterministicForASeedAndDifferentAcrossSeeds) {
  for (GeneratedVolume kind : {GeneratedVolume::kCloud, GeneratedVolume::kSmoke, GeneratedVolume::kFire}) {
    const auto a = generate_grids({kind, 24, 42});
    const auto b = generate_grids({kind, 24, 42});
    const auto c = generate_grids({kind, 24, 43});
    EXPECT_TRUE(identical(a, b)) << int(kind);
    EXPECT_FALSE(identical(a, c)) << int(kind);
  }
}

TEST(GridGenerate, RejectsResolutionsOutsideTheRange) {
  EXPECT_THROW(generate_grids({GeneratedVolume::kCloud, 7, 1}), InputError);
  EXPECT_THROW(generate_grids({GeneratedVolume::kCloud, 1025, 1}), InputError);
  EXPECT_THROW(generate_grids({GeneratedVolume::kCloud, -5, 1}), InputError);
  EXPECT_EQ(parse_generated_volume("fire"), GeneratedVolume::kFire);
  EXPECT_FALSE(parse_generated_volume("explosion").has_value());
}

}  // namespace
}  // namespace caligo
