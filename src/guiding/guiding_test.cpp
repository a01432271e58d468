#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <thread>
#include <vector>

#include "core/error.h"
#include "core/math.h"
#include "core/rng.h"
#include "core/testing/chi_squared.h"
#include "guiding/guiding_field.h"
#include "guiding/guiding_schedule.h"

namespace caligo {
namespace {

// Radiance from one bright cone around +x and a dim sky: what a lamp beside a vertex looks like.
double radiance(Vec3 w) { return (w.x > 0.9f ? 50.0 : 0.0) + (w.z > 0.0f ? 1.0 : 0.1); }

// A tree trained from n uniform directions (value = radiance / uniform pdf), refined `rounds` times.
DirectionalTree trained_tree(int n, int rounds) {
  DirectionalTree tree;
  Pcg32 rng(7, 0);
  for (int r = 0; r < rounds; ++r) {
    for (int i = 0; i < n; ++i) {
      const Vec3 w = square_to_sphere({rng.next_float(), rng.next_float()});
      tree.record(w, radiance(w) * 4.0 * kPi);
    }
    tree = tree.refined(0.01, 20);
  }
  return tree;
}

TEST(Guiding, TheSquareMapIsAnInverse) {
  Pcg32 rng(3, 0);
  for (int i = 0; i < 1000; ++i) {
    const Vec2 p{rng.next_float(), rng.next_float()};
    const Vec2 q = sphere_to_square(square_to_sphere(p));
    EXPECT_NEAR(q.x, p.x, 1e-5f);
    EXPECT_NEAR(std::fmod(q.y - p.y + 1.5f, 1.0f) - 0.5f, 0.0f, 1e-5f);
  }
}

TEST(Guiding, AnUntrainedTreeIsNotUsable) {
  EXPECT_FALSE(DirectionalTree().usable());
  EXPECT_FALSE(DirectionalTree().refined(0.01, 20).usable());
}

// The density over the sphere integrates to one: a midpoint sum over a 1024^2 grid of the square,
// finer than any leaf of this tree above depth 10 (leaves are constant, so the sum is exact for them).
TEST(Guiding, TheGuidedPdfIntegratesToOne) {
  const DirectionalTree tree = trained_tree(20000, 3);
  ASSERT_TRUE(tree.usable());
  ASSERT_GT(tree.node_count(), 10u);
  constexpr int kGrid = 1024;
  double sum = 0.0;
  for (int y = 0; y < kGrid; ++y)
    for (int x = 0; x < kGrid; ++x)
      sum += tree.pdf(square_to_sphere({(x + 0.5f) / kGrid, (y + 0.5f) / kGrid}));
  EXPECT_NEAR(sum * 4.0 * kPi / (kGrid * kGrid), 1.0, 2e-3);
}

// The samples follow the density: chi-squared over 32 x 32 cells of the square, expected counts
// from the pdf integrated over 8 x 8 points per cell.
TEST(Guiding, GuidedSamplesMatchTheirPdf) {
  const DirectionalTree tree = trained_tree(20000, 3);
  constexpr int kCells = 32, kSub = 8, kSamples = 400000;
  std::vector<double> observed(kCells * kCells), expected(kCells * kCells);
  for (int cy = 0; cy < kCells; ++cy)
    for (int cx = 0; cx < kCells; ++cx) {
      double s = 0.0;
      for (int j = 0; j < kSub; ++j)
        for (int i = 0; i < kSub; ++i)
          s += tree.pdf(square_to_sphere({(cx + (i + 0.5f) / kSub) / kCells, (cy + (j + 0.5f) / kSub) / kCells}));
      expected[size_t(cy * kCells + cx)] = s / (kSub * kSub) * 4.0 * kPi / (kCells * kCells) * kSamples;
    }
  Pcg32 rng(11, 0);
  int mismatches = 0;  // directions that round onto the other side of a leaf's edge
  for (int i = 0; i < kSamples; ++i) {
    float pdf = 0.0f;
    const Vec3 w = tree.sample({rng.next_float(), rng.next_float()}, &pdf);
    mismatches += std::abs(pdf - tree.pdf(w)) > 1e-4f * pdf;
    const Vec2 p = sphere_to_square(w);
    observed[size_t(std::min(int(p.y * kCells), kCells - 1) * kCells + std::min(int(p.x * kCells), kCells - 1))] += 1;
  }
  EXPECT_LT(mismatches, kSamples / 5000);
  EXPECT_GT(test_stats::chi2_p_value(observed, expected), 1e-3);
}

// Most of the density goes where the radiance is: the bright cone holds ~60 % of the energy.
TEST(Guiding, TheTreeLearnsWhereTheLightIs) {
  const DirectionalTree tree = trained_tree(20000, 3);
  EXPECT_GT(tree.pdf({1.0f, 0.0f, 0.0f}), 20.0f * tree.pdf({-1.0f, 0.0f, 0.0f}));
}

// The same records from four threads in any interleaving give the same field bit for bit.
TEST(Guiding, TrainingIsTheSameForAnyThreadCount) {
  const auto train = [](int threads) {
    GuidingField field({Vec3(0.0f), Vec3(1.0f)}, {.spatial_threshold = 500});
    for (int it = 0; it < 3; ++it) {
      std::vector<std::thread> pool;
      for (int t = 0; t < threads; ++t)
        pool.emplace_back([&, t] {
          for (int i = t; i < 20000; i += threads) {
            Pcg32 rng{uint64_t(i), uint64_t(it)};
            const Vec3 x{rng.next_float(), rng.next_float(), rng.next_float()};
            const Vec3 w = square_to_sphere({rng.next_float(), rng.next_float()});
            field.record(x, w, radiance(w) * (1.0 + x.x) * 4.0 * kPi);
          }
        });
      for (auto& th : pool) th.join();
      field.finish_iteration();
    }
    return field;
  };
  const GuidingField one = train(1), four = train(4);
  EXPECT_GT(one.spatial_leaves(), 4u);
  EXPECT_EQ(one.to_bytes(), four.to_bytes());
  EXPECT_EQ(one.completed_iterations(), 3);
}

TEST(Guiding, StatisticsWordsSumAcrossFieldsExactly) {
  GuidingField a({Vec3(0.0f), Vec3(1.0f)}), b = a, both = a;
  Pcg32 rng(5, 0);
  for (int i = 0; i < 5000; ++i) {
    const Vec3 x{rng.next_float(), rng.next_float(), rng.next_float()};
    const Vec3 w = square_to_sphere({rng.next_float(), rng.next_float()});
    const double v = radiance(w) * 1e6;  // large values carry across the 32-bit limbs
    (i % 2 ? a : b).record(x, w, v);
    both.record(x, w, v);
  }
  std::vector<uint64_t> words = a.statistics_words();
  const std::vector<uint64_t> other = b.statistics_words();
  for (size_t i = 0; i < words.size(); ++i) words[i] += other[i];
  a.set_statistics_words(words);
  EXPECT_EQ(a.to_bytes(), both.to_bytes());
}

TEST(Guiding, SpatialSplitsStopAtTheMemoryBound) {
  GuidingField field({Vec3(0.0f), Vec3(1.0f)}, {.spatial_threshold = 10, .max_bytes = 64 << 10});
  Pcg32 rng(9, 0);
  for (int it = 0; it < 4; ++it) {
    for (int i = 0; i < 20000; ++i) {
      const Vec3 w = square_to_sphere({rng.next_float(), rng.next_float()});
      field.record({rng.next_float(), rng.next_float(), rng.next_float()}, w, radiance(w));
    }
    field.finish_iteration();
  }
  EXPECT_GT(field.spatial_leaves(), 2u);
  EXPECT_LE(field.memory_bytes(), uint64_t(64) << 10);
}

TEST(Guiding, FieldsRoundTripAndCorruptOnesAreRefused) {
  GuidingField field({Vec3(-1.0f), Vec3(2.0f)}, {.spatial_threshold = 200});
  Pcg32 rng(2, 0);
  for (int it = 0; it < 2; ++it) {
    for (int i = 0; i < 5000; ++i) {
      const Vec3 w = square_to_sphere({rng.next_float(), rng.next_float()});
      field.record({rng.next_float(), rng.next_float(), rng.next_float()}, w, radiance(w));
    }
    field.finish_iteration();
  }
  const std::string bytes = field.to_bytes();
  EXPECT_EQ(GuidingField::from_bytes(bytes, "f").to_bytes(), bytes);
  EXPECT_THROW(GuidingField::from_bytes(bytes.substr(0, bytes.size() - 1), "f"), InputError);
  EXPECT_THROW(GuidingField::from_bytes(bytes + "x", "f"), InputError);
  EXPECT_THROW(GuidingField::from_bytes("CGFIELD2" + bytes.substr(8), "f"), InputError);
  // Every single-byte change is refused or read as a field (never a crash, never a hang).
  for (size_t i = 0; i < bytes.size(); i += std::max<size_t>(1, bytes.size() / 600)) {
    std::string bad = bytes;
    bad[i] = char(bad[i] ^ 0x5a);
    try {
      const GuidingField f = GuidingField::from_bytes(bad, "f");
      float pdf = 0.0f;
      if (const DirectionalTree* t = f.at({0.5f, 0.5f, 0.5f})) t->sample({0.3f, 0.7f}, &pdf);
    } catch (const InputError&) {
    }
  }
}

TEST(Guiding, TheScheduleDoubles) {
  EXPECT_EQ(training_iteration_end(0), 1);
  EXPECT_EQ(training_iteration_end(1), 3);
  EXPECT_EQ(training_iteration_end(8), 511);
}

}  // namespace
}  // namespace caligo
