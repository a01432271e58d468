// Block-DDA intervals against brute force: thousands of random rays through a random sparse
// grid, each sampled every 1/20 voxel; block records against a direct scan of each block's
// 9^3-voxel footprint.
#include "grids/grid_traversal.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/ray_solids.h"
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
  int occupied = 0, constant = 0, tight = 0;
  for (int bz = -17; bz < 18; ++bz)
    for (int by = -17; by < 18; ++by)
      for (int bx = -17; bx < 18; ++bx) {
        float lo = kInfinity, hi = -kInfinity;
        int span_lo[3] = {9, 9, 9}, span_hi[3] = {-1, -1, -1};  // of the non-zero voxels
        for (int i = 0; i <= 8; ++i)
          for (int j = 0; j <= 8; ++j)
            for (int k = 0; k <= 8; ++k) {
              const float v = acc.getValue(Coord(bx * 8 + i, by * 8 + j, bz * 8 + k));
              lo = std::min(lo, v);
              hi = std::max(hi, v);
              if (v == 0.0f) continue;
              const int offset[3] = {i, j, k};
              for (int a = 0; a < 3; ++a) {
                span_lo[a] = std::min(span_lo[a], offset[a]);
                span_hi[a] = std::max(span_hi[a], offset[a]);
              }
            }
        const BlockRecord r = data.blocks.block(bx, by, bz);
        ASSERT_EQ(r.occupied, hi > 0.0f) << bx << " " << by << " " << bz;
        if (!r.occupied) continue;
        EXPECT_EQ(r.majorant, hi);
        EXPECT_EQ(r.minimum, std::max(0.0f, lo));
        EXPECT_EQ(r.constant, lo == hi);
        for (int a = 0; a < 3; ++a) {
          ASSERT_EQ(r.box.lo[a], std::max(0, span_lo[a] - 1)) << bx << " " << by << " " << bz;
          ASSERT_EQ(r.box.hi[a], std::min(8, span_hi[a] + 1)) << bx << " " << by << " " << bz;
        }
        tight += !r.box.full();
        occupied += 1;
        constant += r.constant;
      }
  EXPECT_EQ(uint64_t(occupied), grid->statistics().blocks);
  EXPECT_EQ(uint64_t(constant), grid->statistics().constant_blocks);
  EXPECT_GE(constant, 8);          // the 3^3-block region alone has 8 constant blocks
  EXPECT_GE(tight, occupied / 4);  // the shells around the data at least
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

// Samples the ray every 1/20 voxel and checks each sample against the intervals: the tight boxes
// of occupied blocks are covered by an interval whose majorant bounds the block's and the
// sampled density from above and whose minimum bounds them from below; all else (empty blocks, occupied blocks outside their tight boxes) is not
// covered and reads zero; constant intervals read one value; merged majorants stay within the
// tolerance.
void check_against_samples(const VolumeGrid& grid, const Ray& ray, float t0, float t1, float tolerance,
                           GridAccessorCache& cache) {
  std::vector<GridInterval> iv;
  grid.intervals(ray, t0, t1, iv, tolerance);
  expect_ordered(iv, t0, t1);
  const Bounds3 bounds = grid.world_bounds();
  const auto inside = ray_box(ray.origin, ray.direction, bounds.lo, bounds.hi, t0, t1);
  if (!inside) {
    EXPECT_TRUE(iv.empty());
    return;
  }
  const float b0 = inside->t0, b1 = inside->t1;
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
    const int b[3] = {int(std::floor(x.x / 8)), int(std::floor(x.y / 8)), int(std::floor(x.z / 8))};
    const BlockRecord r = grid.data().blocks.block(b[0], b[1], b[2]);
    bool in_box = r.occupied, near_box_face = false;
    for (int a = 0; a < 3; ++a) {
      const float local = x[a] - 8.0f * float(b[a]);
      in_box = in_box && local >= float(r.box.lo[a]) && local < float(r.box.hi[a]);
      near_box_face = near_box_face || std::abs(local - float(r.box.lo[a])) < 2e-3f ||
                      std::abs(local - float(r.box.hi[a])) < 2e-3f;
    }
    if (near_box_face) continue;  // likewise for a face of a tight box
    const float d = grid.density(ray.at(t), GridFilter::kTrilinear, cache);
    ASSERT_EQ(inside, in_box) << "t " << t << " x " << x.x << " " << x.y << " " << x.z;
    if (!inside) {
      ASSERT_EQ(d, 0.0f);
      continue;
    }
    const GridInterval& g = iv[cursor];
    ASSERT_GE(g.density_max, r.majorant);
    ASSERT_LE(d, g.density_max * (1.0f + 1e-5f) + 1e-6f);
    // The minimum (residual ratio tracking's control) is below every sample and the block's own.
    ASSERT_LE(g.density_min, r.minimum);
    ASSERT_GE(d, g.density_min * (1.0f - 1e-5f) - 1e-6f);
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

// A direction component so small that its reciprocal overflows (here -1e-39, a denormal) on a
// block face: 0 * inf = NaN there must not derail the DDA's choice of axis. The ray is
// indistinguishable from one with that component zero and must get the same intervals.
TEST(GridTraversal, DenormalDirectionOnABlockFaceMatchesAZeroComponent) {
  const auto grid = make_volume_grid({testing::make_nano_grid<float>([](auto& acc) {
                                       for (int i = 0; i < 200; ++i)
                                         for (int j = 0; j < 24; ++j)
                                           for (int k = 0; k < 24; ++k)
                                             acc.setValue(Coord(i, j, k), i < 100 ? 0.001f : 2.0f);
                                     })},
                                     {});
  for (float y : {8.0f, 0.0f, 16.0f}) {
    std::vector<GridInterval> zero, tiny;
    grid->intervals({Vec3(-20.0f, y, 4.5f), Vec3(1.0f, 0.0f, 0.0f)}, 0.0f, 1000.0f, zero, 0.0f);
    grid->intervals({Vec3(-20.0f, y, 4.5f), Vec3(1.0f, -1e-39f, 0.0f)}, 0.0f, 1000.0f, tiny, 0.0f);
    ASSERT_FALSE(zero.empty());
    ASSERT_EQ(tiny.size(), zero.size()) << y;
    for (size_t i = 0; i < zero.size(); ++i) {
      EXPECT_EQ(tiny[i].t0, zero[i].t0);
      EXPECT_EQ(tiny[i].t1, zero[i].t1);
      EXPECT_EQ(tiny[i].density_max, zero[i].density_max);
      EXPECT_EQ(tiny[i].constant, zero[i].constant);
    }
    // The dense half starts at x = 99 (trilinear reads voxel 100 from there): never under a
    // majorant of 0.001.
    for (const GridInterval& i : tiny) {
      if (i.t1 > 99.0f + 20.0f) {
        EXPECT_EQ(i.density_max, 2.0f) << i.t0 << " " << i.t1;
      }
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

// One non-zero voxel at (16, 8, 3), on the shared layers of blocks x 1..2, y 0..1: the
// trilinear density is non-zero only in the open box (15, 17) x (7, 9) x (2, 4), so the intervals
// of any ray must lie within its chord of that box (whole blocks would give ~8 voxels or more).
TEST(GridTraversal, SingleVoxelGivesIntervalsOfItsTrilinearSupport) {
  const auto grid = make_volume_grid(
      {testing::make_nano_grid<float>([](auto& acc) { acc.setValue(Coord(16, 8, 3), 1.0f); })}, {});
  const GridBlocks& blocks = grid->data().blocks;
  EXPECT_EQ(grid->statistics().blocks, 4u);
  const BlockRecord low = blocks.block(1, 0, 0), high = blocks.block(2, 1, 0);
  EXPECT_EQ(low.box.lo, (std::array<uint8_t, 3>{7, 7, 2}));
  EXPECT_EQ(low.box.hi, (std::array<uint8_t, 3>{8, 8, 4}));
  EXPECT_EQ(high.box.lo, (std::array<uint8_t, 3>{0, 0, 2}));
  EXPECT_EQ(high.box.hi, (std::array<uint8_t, 3>{1, 1, 4}));

  // Index = world here. Along x at y = 8.3, z = 3.2: blocks (1, 1, 0) and (2, 1, 0) clipped to
  // x in [15, 16) and [16, 17), merged at the blocks' shared face.
  std::vector<GridInterval> iv;
  grid->intervals({Vec3(-10.0f, 8.3f, 3.2f), Vec3(1.0f, 0.0f, 0.0f)}, 0.0f, 100.0f, iv);
  ASSERT_EQ(iv.size(), 1u);
  EXPECT_EQ(iv[0].t0, 25.0f);
  EXPECT_EQ(iv[0].t1, 27.0f);
  EXPECT_EQ(iv[0].density_max, 1.0f);
  // Along z at x = 15.5, y = 7.5 (block (1, 0, 0) only): z in [2, 4).
  iv.clear();
  grid->intervals({Vec3(15.5f, 7.5f, 10.0f), Vec3(0.0f, 0.0f, -2.0f)}, 0.0f, 100.0f, iv);
  ASSERT_EQ(iv.size(), 1u);
  EXPECT_EQ(iv[0].t0, 3.0f);
  EXPECT_EQ(iv[0].t1, 4.0f);
  // Outside the support on one axis (y = 9.5 is in block (2, 1, 0) but past its tight box).
  iv.clear();
  grid->intervals({Vec3(-10.0f, 9.5f, 3.2f), Vec3(1.0f, 0.0f, 0.0f)}, 0.0f, 100.0f, iv);
  EXPECT_TRUE(iv.empty());

  Pcg32 rng(9, 1);
  GridAccessorCache cache;
  const float chord_bound = 2.0f * std::sqrt(3.0f) + 1e-4f;
  for (int n = 0; n < 2000; ++n) {
    const Vec3 target(15.0f + 2.0f * rng.next_float(), 7.0f + 2.0f * rng.next_float(),
                      2.0f + 2.0f * rng.next_float());
    const Vec3 d = random_direction(rng);
    const Ray ray{target - d * 50.0f, d};
    iv.clear();
    grid->intervals(ray, 0.0f, 100.0f, iv, 1e30f);
    ASSERT_FALSE(iv.empty()) << n;  // the target itself reads a non-zero density
    expect_ordered(iv, 0.0f, 100.0f);
    float total = 0.0f;
    for (const GridInterval& g : iv) total += g.t1 - g.t0;
    ASSERT_LE(total, chord_bound) << n;
    // Each endpoint lies on the support's closed box (up to rounding).
    for (const GridInterval& g : iv)
      for (float t : {g.t0, g.t1}) {
        const Vec3 x = ray.at(t);
        ASSERT_TRUE(x.x > 15.0f - 1e-3f && x.x < 17.0f + 1e-3f && x.y > 7.0f - 1e-3f && x.y < 9.0f + 1e-3f &&
                    x.z > 2.0f - 1e-3f && x.z < 4.0f + 1e-3f)
            << n;
      }
  }
}

}  // namespace
}  // namespace caligo
