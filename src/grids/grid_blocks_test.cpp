// Constant-block detection and the footprint rule (grids/grid_blocks.h), occupancy from
// emission channels, and the intervals of an axis-parallel ray through a constant region.
#include "grids/grid_blocks.h"

#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "grids/grid_accessor_cache.h"
#include "grids/grid_test_grids.h"
#include "grids/volume_grid_data.h"

namespace caligo {
namespace {

using nanovdb::Coord;

// Voxels [0, 24)^3 = 2, optionally with one different voxel.
NanoGridHandle cube_grid(float value = 2.0f, Coord odd = Coord(-1000), float odd_value = 0.0f) {
  return testing::make_nano_grid<float>([&](auto& acc) {
    for (int i = 0; i < 24; ++i)
      for (int j = 0; j < 24; ++j)
        for (int k = 0; k < 24; ++k) acc.setValue(Coord(i, j, k), value);
    if (odd != Coord(-1000)) acc.setValue(odd, odd_value);
  });
}

bool in(int b, int lo, int hi) { return b >= lo && b <= hi; }

TEST(GridBlocks, ConstantRegionObeysTheFootprintRule) {
  const auto grid = make_volume_grid({cube_grid()}, {});
  const GridBlocks& blocks = grid->data().blocks;
  // Block b reads voxels 8b .. 8b+8: it is occupied when that meets [0, 23] (b in -1..2) and
  // constant when it lies inside (b in 0..1) on every axis.
  for (int bz = -3; bz < 5; ++bz)
    for (int by = -3; by < 5; ++by)
      for (int bx = -3; bx < 5; ++bx) {
        const BlockRecord r = blocks.block(bx, by, bz);
        const bool occupied = in(bx, -1, 2) && in(by, -1, 2) && in(bz, -1, 2);
        const bool constant = in(bx, 0, 1) && in(by, 0, 1) && in(bz, 0, 1);
        ASSERT_EQ(r.occupied, occupied) << bx << " " << by << " " << bz;
        ASSERT_EQ(r.constant, constant) << bx << " " << by << " " << bz;
        if (occupied) {
          ASSERT_EQ(r.majorant, 2.0f);
        }
      }
  EXPECT_EQ(grid->statistics().blocks, 64u);
  EXPECT_EQ(grid->statistics().constant_blocks, 8u);
  EXPECT_EQ(grid->statistics().active_voxels, 24u * 24u * 24u);
  EXPECT_EQ(grid->max_density(), 2.0f);
  const Bounds3 b = grid->world_bounds();  // blocks -1..2: index [-8, 24)
  EXPECT_EQ(b.lo, Vec3(-8.0f));
  EXPECT_EQ(b.hi, Vec3(24.0f));
}

TEST(GridBlocks, NeighbourVoxelOnTheSharedLayerBreaksConstancy) {
  // Voxel (16, 4, 4) is the first layer of block (2, 0, 0), which block (1, 0, 0) also reads.
  const auto grid = make_volume_grid({cube_grid(2.0f, Coord(16, 4, 4), 5.0f)}, {});
  const GridBlocks& blocks = grid->data().blocks;
  EXPECT_FALSE(blocks.block(1, 0, 0).constant);
  EXPECT_EQ(blocks.block(1, 0, 0).majorant, 5.0f);
  EXPECT_EQ(blocks.block(2, 0, 0).majorant, 5.0f);
  EXPECT_TRUE(blocks.block(0, 0, 0).constant);
  EXPECT_EQ(blocks.block(0, 0, 0).majorant, 2.0f);
  EXPECT_TRUE(blocks.block(1, 1, 0).constant);
  EXPECT_EQ(grid->statistics().constant_blocks, 7u);
  // Voxel (15, 4, 4) is inside block (1, 0, 0) only.
  const auto inner = make_volume_grid({cube_grid(2.0f, Coord(15, 4, 4), 5.0f)}, {});
  EXPECT_FALSE(inner->data().blocks.block(1, 0, 0).constant);
  EXPECT_TRUE(inner->data().blocks.block(0, 0, 0).constant);
  EXPECT_EQ(inner->data().blocks.block(0, 0, 0).majorant, 2.0f);
}

TEST(GridBlocks, EveryChannelMustBeConstant) {
  auto colours = [](bool varying) {
    return testing::make_nano_grid<nanovdb::Vec3f>([&](auto& acc) {
      for (int i = 0; i < 24; ++i)
        for (int j = 0; j < 24; ++j)
          for (int k = 0; k < 24; ++k)
            acc.setValue(Coord(i, j, k), nanovdb::Vec3f(0.5f, varying ? i * 0.01f : 0.2f, 1.0f));
    });
  };
  NanoGrids uniform{cube_grid()};
  uniform.color = colours(false);
  EXPECT_EQ(make_volume_grid(std::move(uniform), {})->statistics().constant_blocks, 8u);
  NanoGrids varying{cube_grid()};
  varying.color = colours(true);
  EXPECT_EQ(make_volume_grid(std::move(varying), {})->statistics().constant_blocks, 0u);
  NanoGrids hot{cube_grid()};
  hot.temperature = testing::make_nano_grid<float>([](auto& acc) { acc.setValue(Coord(3, 3, 3), 1500.0f); });
  const auto grid = make_volume_grid(std::move(hot), {});
  EXPECT_FALSE(grid->data().blocks.block(0, 0, 0).constant);
  EXPECT_TRUE(grid->data().blocks.block(1, 0, 0).constant);
}

// A Cd grid on another transform is looked up through its own map, so the blocks cannot vouch
// for it: a block that is constant in density but whose colour varies would be shaded at one
// point while its extinction (sigma_s is tinted) varies. No block may then be constant.
TEST(GridBlocks, ColorOnAnotherTransformMakesNoBlockConstant) {
  NanoGrids grids{cube_grid()};
  grids.color = testing::make_nano_grid<nanovdb::Vec3f>(
      [](auto& acc) {
        for (int i = 0; i < 48; ++i)
          for (int j = 0; j < 48; ++j)
            for (int k = 0; k < 48; ++k) acc.setValue(Coord(i, j, k), nanovdb::Vec3f(0.5f, i / 48.0f, 1.0f));
      },
      0.5);
  const auto grid = make_volume_grid(std::move(grids), {});
  ASSERT_FALSE(grid->data().color_shares_index_space);
  GridAccessorCache cache;
  // The colour does vary inside block (0, 0, 0), which is constant in density.
  EXPECT_NE(grid->values(Vec3(1.0f, 4.0f, 4.0f), GridFilter::kTrilinear, cache).color.g,
            grid->values(Vec3(6.0f, 4.0f, 4.0f), GridFilter::kTrilinear, cache).color.g);
  EXPECT_EQ(grid->statistics().constant_blocks, 0u);
  EXPECT_FALSE(grid->data().blocks.block(0, 0, 0).constant);
  std::vector<GridInterval> iv;
  grid->intervals({Vec3(-20.0f, 4.5f, 4.5f), Vec3(1.0f, 0.0f, 0.0f)}, 0.0f, 100.0f, iv);
  ASSERT_FALSE(iv.empty());
  for (const GridInterval& i : iv) EXPECT_FALSE(i.constant);
}

TEST(GridBlocks, EmissionAloneOccupiesBlocks) {
  // A fireball's flame may burn where there is no smoke: density is empty here.
  NanoGrids fire{testing::make_nano_grid<float>([](auto&) {})};
  fire.flame = testing::make_nano_grid<float>([](auto& acc) {
    for (int i = 0; i < 8; ++i) acc.setValue(Coord(40 + i, 4, 4), 3.0f);
  });
  const auto grid = make_volume_grid(std::move(fire), {});
  EXPECT_EQ(grid->max_density(), 0.0f);
  EXPECT_TRUE(grid->data().blocks.block(5, 0, 0).occupied);
  EXPECT_TRUE(grid->data().blocks.block(4, 0, 0).occupied);  // reads voxel (40, 4, 4)
  std::vector<GridInterval> iv;
  grid->intervals({Vec3(0.0f, 4.0f, 4.0f), Vec3(1.0f, 0.0f, 0.0f)}, 0.0f, 100.0f, iv);
  ASSERT_EQ(iv.size(), 1u);
  EXPECT_EQ(iv[0].t0, 39.0f);  // block 4 clipped to its tight box, x in [39, 40)
  EXPECT_EQ(iv[0].t1, 48.0f);
  EXPECT_EQ(iv[0].density_max, 0.0f);
  GridAccessorCache cache;
  EXPECT_EQ(grid->values(Vec3(44.0f, 4.0f, 4.0f), GridFilter::kNearest, cache).flame, 3.0f);
  EXPECT_FLOAT_EQ(grid->values(Vec3(39.5f, 4.0f, 4.0f), GridFilter::kTrilinear, cache).flame, 1.5f);
}

// The shell of blocks around the cube reads it only through its last voxel layer on the axes
// where it lies outside; other blocks keep the full region.
TEST(GridBlocks, ShellBlocksHaveOneLayerTightBoxes) {
  const auto grid = make_volume_grid({cube_grid()}, {});
  const GridBlocks& blocks = grid->data().blocks;
  using A = std::array<uint8_t, 3>;
  EXPECT_EQ(blocks.block(-1, 0, 1).box.lo, (A{7, 0, 0}));
  EXPECT_EQ(blocks.block(-1, 0, 1).box.hi, (A{8, 8, 8}));
  EXPECT_EQ(blocks.block(-1, -1, -1).box.lo, (A{7, 7, 7}));
  EXPECT_EQ(blocks.block(-1, -1, -1).box.hi, (A{8, 8, 8}));
  EXPECT_EQ(blocks.block(2, -1, 0).box.lo, (A{0, 7, 0}));  // voxels 16..23 of x: offsets 0..7
  EXPECT_EQ(blocks.block(2, -1, 0).box.hi, (A{8, 8, 8}));
  EXPECT_TRUE(blocks.block(2, 0, 0).box.full());  // non-constant, but data reaches every voxel
  EXPECT_TRUE(blocks.block(1, 1, 1).box.full());  // constant
  // A ray through the corner shell block (-1, -1, -1) along its diagonal crosses the tight box
  // [-1, 0)^3 only: t in [7, 8) for x = t - 8.
  std::vector<GridInterval> iv;
  grid->intervals({Vec3(-8.0f), Vec3(1.0f)}, 0.0f, 7.5f, iv);
  ASSERT_EQ(iv.size(), 1u);
  EXPECT_EQ(iv[0].t0, 7.0f);
  EXPECT_EQ(iv[0].t1, 7.5f);
}

TEST(GridBlocks, AxisRayThroughConstantRegionGivesAnalyticIntervals) {
  const auto grid = make_volume_grid({cube_grid()}, {});
  std::vector<GridInterval> iv;
  // Index = world here (unit voxels at the origin); t = x + 10.
  grid->intervals({Vec3(-10.0f, 4.5f, 4.5f), Vec3(1.0f, 0.0f, 0.0f)}, 0.0f, 100.0f, iv, 0.25f);
  ASSERT_EQ(iv.size(), 3u);
  EXPECT_EQ(iv[0].t0, 9.0f);  // block -1 reads voxel 0 only, in its last layer: [-1, 0)
  EXPECT_EQ(iv[0].t1, 10.0f);
  EXPECT_FALSE(iv[0].constant);
  EXPECT_EQ(iv[1].t0, 10.0f);  // blocks 0 and 1, constant, merged: [0, 16)
  EXPECT_EQ(iv[1].t1, 26.0f);
  EXPECT_TRUE(iv[1].constant);
  EXPECT_EQ(iv[1].density_max, 2.0f);
  EXPECT_EQ(iv[2].t0, 26.0f);  // block 2 reads the zero layer at x = 24: [16, 24)
  EXPECT_EQ(iv[2].t1, 34.0f);
  EXPECT_FALSE(iv[2].constant);
  // Starting inside a constant block, ending inside the non-constant block 2 (x = 16 at t = 6.5).
  iv.clear();
  grid->intervals({Vec3(3.0f, 4.5f, 4.5f), Vec3(2.0f, 0.0f, 0.0f)}, 0.0f, 8.0f, iv, 0.25f);
  ASSERT_EQ(iv.size(), 2u);
  EXPECT_EQ(iv[0].t0, 0.0f);
  EXPECT_EQ(iv[0].t1, 6.5f);
  EXPECT_TRUE(iv[0].constant);
  EXPECT_EQ(iv[1].t0, 6.5f);
  EXPECT_EQ(iv[1].t1, 8.0f);
  EXPECT_FALSE(iv[1].constant);
}

}  // namespace
}  // namespace caligo
