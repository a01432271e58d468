// Block-DDA intervals against brute force: thousands of random rays through a random sparse
// grid, each sampled every 1/20 voxel; block records against a direct scan of each block's
// 9^3-voxel footprint.
#include "grids/grid_traversal.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/rng.h"
#include "grids/grid_accessor_cache.h"
#include "grids/grid_test_grids.h"
#include "grids/volume_grid_data.h"

namespace caligo {
namespace {

using nanovdb::Coord;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kVoxel = 0.25f;
const Vec3 kOrigin(1.0f, -2.0f, 0.5f);  // world position of index (0, 0, 0)

Vec3 index_to_world(Vec3 x) { return kOrigin + x * kVoxel; }
Vec3 world_to_index(Vec3 p) { return (p - kOrigin) / kVoxel; }

// Blocks in [-6, 6)^3: constant blocks, noisy blocks of random scale, a few isolated voxels, and
// a 3^3-block constant region (whose inner blocks are constant over their footprints).
std::shared_ptr<const VolumeGrid> random_sparse_grid(uint64_t seed) {
  Pcg32 rng(seed, 7);
  auto fill = [&](auto& acc) {
    for (int n = 0; n < 70; ++n) {
      const int bx = int(rng.next_u32() % 12) - 6, by = int(rng.next_u32() % 12) - 6,
                bz = int(rng.next_u32() % 12) - 6;
      const float kind = rng.next_float(), scale = 0.1f + 4.0f * rng.next_float();
      for (int i = 0; i < 8; ++i)
        for (int j = 0; j < 8; ++j)
          for (int k = 0; k < 8; ++k) {
            const Coord c(bx * 8 + i, by * 8 + j, bz * 8 + k);
            if (kind < 0.3f) {
              acc.setValue(c, scale);
            } else if (kind < 0.8f) {
              acc.setValue(c, scale * testing::hash01(c[0], c[1], c[2], uint32_t(seed)));
            } else if (testing::hash01(c[0], c[1], c[2], uint32_t(seed) + 1) < 0.02f) {
              acc.setValue(c, scale);
            }
          }
    }
    // Blocks on the low corner of an otherwise empty parent: their footprint reaches into the
    // parents below.
    for (const Coord b : {Coord(16, 0, 0), Coord(0, -8, 16), Coord(8, 8, -16)})
      for (int i = 0; i < 8; ++i)
        for (int j = 0; j < 8; ++j)
          for (int k = 0; k < 8; ++k)
            acc.setValue(Coord(b[0] * 8 + i, b[1] * 8 + j, b[2] * 8 + k), 0.5f + float(i + j + k) / 8.0f);
    for (int i = 40; i < 64; ++i)
      for (int j = -24; j < 0; ++j)
        for (int k = 0; k < 24; ++k) acc.setValue(Coord(i, j, k), 1.5f);
  };
  NanoGrids grids{
      testing::make_nano_grid<float>(fill, kVoxel, nanovdb::Vec3d(kOrigin.x, kOrigin.y, kOrigin.z))};
  return make_volume_grid(std::move(grids), {"random.nvdb", ""});
}

TEST(GridBlocks, RecordsMatchBruteForceFootprintScan) {
  const auto grid = random_sparse_grid(1);
  const VolumeGridData& data = grid->data();
  auto acc = data.density->getAccessor();
  int occupied = 0, constant = 0;
  for (int bz = -17; bz < 18; ++bz)
    for (int by = -17; by < 18; ++by)
      for (int bx = -17; bx < 18; ++bx) {
        float lo = kInfinity, hi = -kInfinity;
        for (int i = 0; i <= 8; ++i)
          for (int j = 0; j <= 8; ++j)
            for (int k = 0; k <= 8; ++k) {
              const float v = acc.getValue(Coord(bx * 8 + i, by * 8 + j, bz * 8 + k));
              lo = std::min(lo, v);
              hi = std::max(hi, v);
            }
        const BlockRecord r = data.blocks.block(bx, by, bz);
        ASSERT_EQ(r.occupied, hi > 0.0f) << bx << " " << by << " " << bz;
        if (!r.occupied) continue;
        EXPECT_EQ(r.majorant, hi);
        EXPECT_EQ(r.constant, lo == hi);
        occupied += 1;
        constant += r.constant;
      }
  EXPECT_EQ(uint64_t(occupied), grid->statistics().blocks);
  EXPECT_EQ(uint64_t(constant), grid->statistics().constant_blocks);
  EXPECT_GE(constant, 8);  // the 3^3-block region alone has 8 constant blocks
}

void expect_ordered(const std::vector<GridInterval>& iv, float t0, float t1) {
  for (size_t i = 0; i < iv.size(); ++i) {
    ASSERT_TRUE(std::isfinite(iv[i].t0) && std::isfinite(iv[i].t1) && std::isfinite(iv[i].density_max));
    ASSERT_LT(iv[i].t0, iv[i].t1);
    ASSERT_GE(iv[i].t0, t0);
    ASSERT_LE(iv[i].t1, t1);
    if (i > 0) {
      ASSERT_LE(iv[i - 1].t1, iv[i].t0);
    }
  }
}

// Samples the ray every 1/20 voxel and checks each sample against the intervals: occupied blocks
// are covered by an interval whose majorant bounds the block's and the sampled density; empty
// blocks are not covered and read zero; constant intervals read one value; merged majorants stay
// within the tolerance.
void check_against_samples(const VolumeGrid& grid, const Ray& ray, float t0, float t1, float tolerance,
                           GridAccessorCache& cache) {
  std::vector<GridInterval> iv;
  grid.intervals(ray, t0, t1, iv, tolerance);
  expect_ordered(iv, t0, t1);
  float b0 = t0, b1 = t1;
  Ray clip = ray;
  clip.tmin = t0;
  clip.tmax = t1;
  if (!grid.world_bounds().intersect(clip, &b0, &b1)) {
    EXPECT_TRUE(iv.empty());
    return;
  }
  const float index_length = length(ray.direction) / kVoxel * (b1 - b0);
  const int n = std::min(20000, std::max(16, int(index_length * 20.0f)));
  std::vector<float> lo(iv.size(), kInfinity), hi(iv.size(), 0.0f), first(iv.size(), -1.0f);
  size_t cursor = 0;
  for (int s = 0; s < n; ++s) {
    const float t = b0 + (b1 - b0) * (float(s) + 0.5f) / float(n);
    const Vec3 x = world_to_index(ray.at(t));
    float to_plane = kInfinity;
    for (int a = 0; a < 3; ++a)
      to_plane = std::min(to_plane, std::abs(x[a] - 8.0f * std::round(x[a] / 8.0f)));
    while (cursor < iv.size() && iv[cursor].t1 < t) ++cursor;
    const bool inside = cursor < iv.size() && iv[cursor].t0 <= t && t <= iv[cursor].t1;
    if (to_plane < 2e-3f) continue;  // a sample on a block face may round into either block
    const BlockRecord r = grid.data().blocks.block(int(std::floor(x.x / 8)), int(std::floor(x.y / 8)),
                                                   int(std::floor(x.z / 8)));
    const float d = grid.density(ray.at(t), GridFilter::kTrilinear, cache);
    ASSERT_EQ(inside, r.occupied) << "t " << t << " x " << x.x << " " << x.y << " " << x.z;
    if (!inside) {
      ASSERT_EQ(d, 0.0f);
      continue;
    }
    const GridInterval& g = iv[cursor];
    ASSERT_GE(g.density_max, r.majorant);
    ASSERT_LE(d, g.density_max * (1.0f + 1e-5f) + 1e-6f);
    if (g.constant) {
      ASSERT_TRUE(r.constant);
      if (first[cursor] < 0.0f) first[cursor] = d;
      ASSERT_NEAR(d, first[cursor], 1e-5f * first[cursor]);
    }
    lo[cursor] = std::min(lo[cursor], r.majorant);
    hi[cursor] = std::max(hi[cursor], r.majorant);
  }
  for (size_t i = 0; i < iv.size(); ++i) {
    if (lo[i] > hi[i]) continue;  // too short to be sampled
    EXPECT_LE(hi[i], iv[i].density_max);
    if (tolerance == 0.0f) {
      EXPECT_EQ(hi[i], iv[i].density_max);
    }
    if (!iv[i].constant) {
      EXPECT_LE(hi[i], lo[i] * (1.0f + tolerance) * (1.0f + 1e-6f));
    }
  }
}

Vec3 random_direction(Pcg32& rng) {
  const float z = 1.0f - 2.0f * rng.next_float(), phi = 2.0f * kPi * rng.next_float();
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

TEST(GridTraversal, IntervalsMatchBruteForceOnRandomRays) {
  const auto grid = random_sparse_grid(2);
  GridAccessorCache cache;
  Pcg32 rng(42, 3);
  const float tolerances[3] = {0.0f, 0.25f, 1e30f};
  for (int n = 0; n < 3000; ++n) {
    Vec3 o(rng.next_float() * 320.0f - 160.0f, rng.next_float() * 320.0f - 160.0f,
           rng.next_float() * 320.0f - 160.0f);
    Vec3 d = random_direction(rng) * (0.05f + 5.0f * rng.next_float());
    const int kind = n % 4;
    if (kind == 0) {  // aimed at a point inside the grid
      const Vec3 target(rng.next_float() * 200.0f - 64.0f, rng.next_float() * 200.0f - 64.0f,
                        rng.next_float() * 200.0f - 64.0f);
      d = normalize(target - o) * length(d);
    }
    if (kind == 1) {  // axis-parallel, often exactly on block planes
      d = Vec3(0.0f);
      d[int(rng.next_u32() % 3)] = rng.next_float() < 0.5f ? -1.0f : 1.0f;
      for (int a = 0; a < 3; ++a)
        if (rng.next_float() < 0.5f) o[a] = 8.0f * float(int(rng.next_u32() % 14) - 7);
    } else if (kind == 2) {  // in a coordinate plane
      d[int(rng.next_u32() % 3)] = 0.0f;
    } else if (kind == 3) {  // starting inside the grid
      o = o * 0.4f;
    }
    const Ray ray{index_to_world(o), d * kVoxel};
    const float t0 = kind == 3 ? 0.0f : -1e4f, t1 = kind == 3 ? 30.0f + rng.next_float() * 100.0f : 1e4f;
    SCOPED_TRACE(n);
    check_against_samples(*grid, ray, t0, t1, tolerances[n % 3], cache);
    if (HasFatalFailure()) return;
  }
}

TEST(GridTraversal, DegenerateRaysYieldNothing) {
  const auto grid = random_sparse_grid(3);
  std::vector<GridInterval> iv;
  const Ray through{index_to_world(Vec3(-100.0f, 3.0f, 5.0f)), Vec3(1.0f, 0.01f, 0.02f)};
  grid->intervals(through, 5.0f, 5.0f, iv);                        // zero-length range
  grid->intervals(through, 10.0f, 5.0f, iv);                       // reversed range
  grid->intervals({through.origin, Vec3(0.0f)}, 0.0f, 1e30f, iv);  // no direction
  grid->intervals({Vec3(kNaN, 0.0f, 0.0f), through.direction}, 0.0f, 100.0f, iv);
  grid->intervals(through, kNaN, 100.0f, iv);
  grid->intervals({index_to_world(Vec3(-100.0f, 500.0f, 5.0f)), Vec3(1.0f, 0.0f, 0.0f)}, 0.0f, 1e30f,
                  iv);  // misses
  EXPECT_TRUE(iv.empty());
  grid->intervals(through, 0.0f, kInfinity, iv);  // an infinite range is clipped to the grid
  EXPECT_FALSE(iv.empty());
  expect_ordered(iv, 0.0f, kInfinity);
}

TEST(GridTraversal, GrazingAndBoundaryRaysStayOrdered) {
  const auto grid = random_sparse_grid(4);
  const GridBlocks& b = grid->data().blocks;
  GridAccessorCache cache;
  // Along the faces and edges of the occupied box, and along interior block planes.
  const float lo = float(b.block_lo[1] * 8), hi = float((b.block_hi[1] + 1) * 8);
  for (float y : {lo, hi, 0.0f, 8.0f, -8.0f}) {
    for (float z : {float(b.block_lo[2] * 8), float((b.block_hi[2] + 1) * 8), 0.0f, 16.0f}) {
      const Ray ray{index_to_world(Vec3(-200.0f, y, z)), Vec3(kVoxel, 0.0f, 0.0f)};
      check_against_samples(*grid, ray, 0.0f, 1000.0f, 0.25f, cache);
      const Ray diagonal{index_to_world(Vec3(-200.0f, y - 200.0f, z)), Vec3(kVoxel, kVoxel, 0.0f)};
      check_against_samples(*grid, diagonal, 0.0f, 1000.0f, 0.25f, cache);
    }
  }
}

TEST(GridTraversal, AppendsWithoutMergingIntoEarlierIntervals) {
  const auto grid = random_sparse_grid(5);
  const Ray ray{index_to_world(Vec3(-100.0f, 2.0f, 3.0f)), Vec3(kVoxel, 0.0f, 0.0f)};
  std::vector<GridInterval> alone;
  grid->intervals(ray, 0.0f, 1000.0f, alone, 1e30f);
  ASSERT_FALSE(alone.empty());
  std::vector<GridInterval> iv{{-1.0f, alone[0].t0, 1e6f, false}};
  grid->intervals(ray, 0.0f, 1000.0f, iv, 1e30f);
  ASSERT_EQ(iv.size(), alone.size() + 1);
  EXPECT_EQ(iv[0].t1, alone[0].t0);
  EXPECT_EQ(iv[0].density_max, 1e6f);
  EXPECT_EQ(iv[1].t0, alone[0].t0);
}

}  // namespace
}  // namespace caligo
