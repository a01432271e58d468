// Lookups against OpenVDB's own box sampler on the same values, NanoVDB tiles, statistics and
// memory of a realistic grid, and the errors make_volume_grid raises. The only test file that
// includes OpenVDB (to build reference grids and tiles).
#include "grids/volume_grid.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <nanovdb/util/OpenToNanoVDB.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>

#include "core/rng.h"
#include "grids/grid_accessor_cache.h"
#include "grids/grid_test_grids.h"
#include "grids/volume_grid_data.h"

namespace caligo {
namespace {

class VolumeGridTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { openvdb::initialize(); }
};

// Noisy values in a few sparse regions of [-40, 40)^3, on a power-of-two voxel so that
// world <-> index conversions of dyadic points are exact in float.
openvdb::FloatGrid::Ptr reference_grid(openvdb::math::Transform::Ptr transform) {
  auto grid = openvdb::FloatGrid::create(0.0f);
  grid->setTransform(transform);
  auto acc = grid->getAccessor();
  for (int i = -40; i < 40; ++i)
    for (int j = -40; j < 40; ++j)
      for (int k = -40; k < 40; ++k) {
        const float h = testing::hash01(i >> 3, j >> 3, k >> 3, 9);
        if (h < 0.5f) acc.setValue(openvdb::Coord(i, j, k), testing::hash01(i, j, k, 11) * (1.0f + 3.0f * h));
      }
  return grid;
}

std::shared_ptr<const VolumeGrid> to_volume_grid(const openvdb::FloatGrid& grid) {
  return make_volume_grid({nanovdb::openToNanoVDB(grid)}, {"test.vdb", ""});
}

TEST_F(VolumeGridTest, TrilinearAndNearestMatchOpenVdb) {
  auto transform = openvdb::math::Transform::createLinearTransform(0.5);
  transform->postTranslate(openvdb::Vec3d(1.25, -3.0, 0.5));
  const auto vdb = reference_grid(transform);
  const auto grid = to_volume_grid(*vdb);
  openvdb::tools::GridSampler<openvdb::FloatGrid, openvdb::tools::BoxSampler> box(*vdb);
  auto acc = vdb->getConstAccessor();
  GridAccessorCache cache;
  Pcg32 rng(5, 1);
  int nonzero = 0;
  for (int n = 0; n < 20000; ++n) {
    // Index points on a 1/1024 lattice: exactly representable before and after the map.
    Vec3 x;
    for (int a = 0; a < 3; ++a) x[a] = float(int(rng.next_u32() % (100 * 1024)) - 50 * 1024) / 1024.0f;
    const Vec3 p = Vec3(1.25f, -3.0f, 0.5f) + x * 0.5f;
    const float expected = box.isSample(openvdb::Vec3d(x.x, x.y, x.z));
    const float got = grid->density(p, GridFilter::kTrilinear, cache);
    ASSERT_NEAR(got, expected, 1e-6f * std::max(1.0f, std::abs(expected))) << x.x << " " << x.y << " " << x.z;
    const openvdb::Coord nearest(int(std::floor(x.x + 0.5f)), int(std::floor(x.y + 0.5f)),
                                 int(std::floor(x.z + 0.5f)));
    ASSERT_EQ(grid->density(p, GridFilter::kNearest, cache), acc.getValue(nearest));
    const GridValues v = grid->values(p, GridFilter::kTrilinear, cache);
    ASSERT_EQ(v.density, got);
    ASSERT_EQ(v.temperature, 0.0f);
    ASSERT_EQ(v.color, RGB(1.0f));
    nonzero += expected > 0.0f;
  }
  EXPECT_GT(nonzero, 5000);
  EXPECT_EQ(grid->density(Vec3(1e30f, 0.0f, 0.0f), GridFilter::kTrilinear, cache), 0.0f);
  EXPECT_FLOAT_EQ(grid->voxel_size(), 0.5f);
}

TEST_F(VolumeGridTest, RotatedTransformMatchesOpenVdbWorldSampling) {
  auto transform = openvdb::math::Transform::createLinearTransform(0.3);
  transform->postRotate(0.7, openvdb::math::Z_AXIS);
  transform->postRotate(0.4, openvdb::math::X_AXIS);
  transform->postTranslate(openvdb::Vec3d(2.0, 1.0, -1.0));
  const auto vdb = reference_grid(transform);
  const auto grid = to_volume_grid(*vdb);
  openvdb::tools::GridSampler<openvdb::FloatGrid, openvdb::tools::BoxSampler> box(*vdb);
  GridAccessorCache cache;
  Pcg32 rng(6, 1);
  const Bounds3 bounds = grid->world_bounds();
  for (int n = 0; n < 5000; ++n) {
    const Vec3 p =
        bounds.lo + mul(bounds.diagonal(), Vec3(rng.next_float(), rng.next_float(), rng.next_float()));
    const float expected = box.wsSample(openvdb::Vec3d(p.x, p.y, p.z));
    // float vs double world-to-index: ~1e-5 voxel of position error times a gradient <= 4 per voxel
    ASSERT_NEAR(grid->density(p, GridFilter::kTrilinear, cache), expected, 1e-4f);
  }
  // Every non-zero voxel's world position lies inside the bounds.
  for (auto it = vdb->cbeginValueOn(); it; ++it) {
    const openvdb::Vec3d w = vdb->indexToWorld(it.getCoord());
    ASSERT_TRUE(bounds.contains(Vec3(float(w.x()), float(w.y()), float(w.z()))));
  }
}

TEST_F(VolumeGridTest, TilesAreConstantBlocks) {
  auto vdb = openvdb::FloatGrid::create(0.0f);
  vdb->tree().addTile(2, openvdb::Coord(0, 0, 0), 1.5f, true);    // a 128^3 tile
  vdb->tree().addTile(1, openvdb::Coord(200, 0, 0), 2.0f, true);  // an 8^3 tile
  const auto grid = to_volume_grid(*vdb);
  ASSERT_GT(grid->data().density->tree().nodeCount(1), 0u);
  EXPECT_EQ(grid->data().density->tree().nodeCount(0), 0u);  // no leaves: tiles only
  const GridStatistics s = grid->statistics();
  EXPECT_EQ(s.active_voxels, 128u * 128u * 128u + 512u);
  // Blocks -1..15 per axis for the big tile (0..14 constant), 24..25 for the small one.
  EXPECT_EQ(s.blocks, 17u * 17u * 17u + 8u);
  EXPECT_EQ(s.constant_blocks, 15u * 15u * 15u);
  EXPECT_EQ(s.min_value, 1.5f);
  EXPECT_EQ(s.max_value, 2.0f);
  GridAccessorCache cache;
  EXPECT_EQ(grid->density(Vec3(60.3f, 7.7f, 100.1f), GridFilter::kTrilinear, cache), 1.5f);
  EXPECT_EQ(grid->density(Vec3(204.0f, 3.0f, 3.0f), GridFilter::kTrilinear, cache), 2.0f);
  std::vector<GridInterval> iv;
  grid->intervals({Vec3(-20.0f, 50.0f, 50.0f), Vec3(1.0f, 0.0f, 0.0f)}, 0.0f, 1000.0f, iv);
  ASSERT_EQ(iv.size(), 3u);  // the big tile's rim, its constant interior, the far rim
  EXPECT_EQ(iv[1].t0, 20.0f);
  EXPECT_EQ(iv[1].t1, 140.0f);
  EXPECT_TRUE(iv[1].constant);
}

TEST_F(VolumeGridTest, NoisySphereStatisticsAndMemory) {
  uint64_t active = 0;
  float lo = kInfinity, hi = 0.0f;
  auto handle = testing::make_nano_grid<float>(
      [&](auto& acc) {
        for (int i = -64; i < 64; ++i)
          for (int j = -64; j < 64; ++j)
            for (int k = -64; k < 64; ++k) {
              const float r = std::sqrt(float(i * i + j * j + k * k)) / 60.0f;
              if (r >= 1.0f) continue;
              const float v = (1.0f - r) * (0.2f + testing::hash01(i >> 1, j >> 1, k >> 1, 3));
              acc.setValue(nanovdb::Coord(i, j, k), v);
              ++active;
              lo = std::min(lo, v);
              hi = std::max(hi, v);
            }
      },
      0.01);
  const auto grid = make_volume_grid({std::move(handle)}, {});
  const GridStatistics s = grid->statistics();
  EXPECT_EQ(s.active_voxels, active);
  EXPECT_EQ(s.min_value, lo);
  EXPECT_EQ(s.max_value, hi);
  EXPECT_EQ(grid->max_density(), hi);
  EXPECT_GT(s.blocks, grid->data().density->tree().nodeCount(0));  // leaves plus the -x/-y/-z rim
  EXPECT_LE(double(grid->memory_bytes()), 1.5 * double(grid->nanovdb_bytes()));
  EXPECT_GT(grid->memory_bytes(), grid->nanovdb_bytes());
  std::printf(
      "noisy sphere 128^3: %llu active voxels, %llu blocks, nanovdb %zu bytes, loaded %zu bytes (%.3fx)\n",
      (unsigned long long)s.active_voxels, (unsigned long long)s.blocks, grid->nanovdb_bytes(),
      grid->memory_bytes(), double(grid->memory_bytes()) / double(grid->nanovdb_bytes()));
}

std::string error_of(NanoGrids grids) {
  try {
    make_volume_grid(std::move(grids), {"bad.vdb", ""});
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

NanoGridHandle one_voxel(float v, double voxel = 1.0) {
  return testing::make_nano_grid<float>([&](auto& acc) { acc.setValue(nanovdb::Coord(1, 2, 3), v); }, voxel);
}

TEST_F(VolumeGridTest, InvalidInputIsALocatedError) {
  auto has = [](const std::string& what, const std::string& part) {
    return what.find(part) != std::string::npos && what.find("bad.vdb") == 0;
  };
  auto vec3 = testing::make_nano_grid<nanovdb::Vec3f>(
      [](auto& acc) { acc.setValue(nanovdb::Coord(0), nanovdb::Vec3f(1.0f)); });
  EXPECT_PRED2(has, error_of({std::move(vec3)}), "'density' must be a float grid");
  NanoGrids wrong_color{one_voxel(1.0f)};
  wrong_color.color = one_voxel(1.0f);
  EXPECT_PRED2(has, error_of(std::move(wrong_color)), "'Cd' must be a vec3 float grid");
  EXPECT_PRED2(has, error_of({NanoGridHandle()}), "'density' is empty or not a NanoVDB grid");
  EXPECT_PRED2(has, error_of({one_voxel(std::nanf(""))}), "non-finite value");
  EXPECT_PRED2(has, error_of({one_voxel(-0.5f)}), "negative value -0.5 at voxel (1, 2, 3)");
  NanoGrids hot{one_voxel(1.0f)};
  hot.temperature = one_voxel(std::numeric_limits<float>::infinity());
  EXPECT_PRED2(has, error_of(std::move(hot)), "'temperature' has a non-finite value");
  NanoGrids scaled{one_voxel(1.0f)};
  scaled.flame = one_voxel(1.0f, 2.0);
  EXPECT_PRED2(has, error_of(std::move(scaled)), "'flame' has a different transform");
  EXPECT_PRED2(has, error_of({testing::make_nano_grid<float>([](auto&) {})}), "'density' is empty");
  EXPECT_PRED2(has, error_of({testing::make_nano_grid<float>([](auto&) {}, 1.0, nanovdb::Vec3d(0.0), 0.5f)}),
               "background 0.5");
  EXPECT_PRED2(has, error_of({testing::make_nano_grid<float>([](auto& acc) {
                 acc.setValue(nanovdb::Coord(0), 1.0f);
                 acc.setValue(nanovdb::Coord(1 << 24, 1 << 24, 0), 1.0f);
               })}),
               "too large/sparse");
  // A file's forward map (world bounds) and inverse map (lookups, traversal) are stored
  // separately: a non-finite or inconsistent pair would place the grid's box and its voxels
  // apart, or give NaN bounds.
  for (int corrupt = 0; corrupt < 4; ++corrupt) {
    NanoGridHandle handle = one_voxel(1.0f);
    nanovdb::Map& map = reinterpret_cast<nanovdb::GridData*>(handle.data())->mMap;
    if (corrupt == 0) map.mMatD[0] = map.mMatF[0] = std::numeric_limits<float>::infinity();
    if (corrupt == 1) map.mVecD[1] = std::nan("");
    // 2: the map is no longer the inverse's inverse; 3: the float inverse disagrees with the map.
    if (corrupt == 2) map.mMatD[4] = map.mMatF[4] = 3.0f;
    if (corrupt == 3) map.mInvMatF[0] = 0.5f;
    EXPECT_PRED2(has, error_of({std::move(handle)}), "'density' has a degenerate or non-finite transform")
        << corrupt;
  }
  auto huge = openvdb::FloatGrid::create(0.0f);
  huge->tree().addTile(3, openvdb::Coord(0), 1.0f, true);  // one 4096^3 root tile
  EXPECT_PRED2(has, error_of({nanovdb::openToNanoVDB(*huge)}), "too large");
}

}  // namespace
}  // namespace caligo
