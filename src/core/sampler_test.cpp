// Tests of the scrambled Sobol' sampler: range, determinism, independence across pixels, seeds and
// dimensions, and the stratification that justifies using it (a (0, m, 2)-net per pixel).
#include "core/sampler.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <set>
#include <vector>

namespace caligo {
namespace {

// Each elementary interval of shape 2^a x 2^(m-a) holds exactly one of the 2^m points.
void expect_0m2_net(const std::vector<Vec2>& points, int m) {
  ASSERT_EQ(points.size(), size_t(1) << m);
  for (int a = 0; a <= m; ++a) {
    const int nx = 1 << a, ny = 1 << (m - a);
    std::vector<int> count(size_t(nx) * size_t(ny), 0);
    for (Vec2 p : points) ++count[size_t(int(p.x * nx) * ny + int(p.y * ny))];
    for (int c : count) ASSERT_EQ(c, 1) << "intervals " << nx << " x " << ny;
  }
}

std::vector<Vec2> pixel_points_2d(uint64_t seed, Vec2i pixel, uint32_t dim, uint32_t first, uint32_t n) {
  std::vector<Vec2> points;
  for (uint32_t i = first; i < first + n; ++i) points.push_back(Sampler(seed, pixel, i).get_2d(dim));
  return points;
}

std::vector<float> pixel_values_1d(uint64_t seed, Vec2i pixel, uint32_t dim, uint32_t n) {
  std::vector<float> values;
  for (uint32_t i = 0; i < n; ++i) values.push_back(Sampler(seed, pixel, i).get_1d(dim));
  return values;
}

}  // namespace

TEST(SobolBuildingBlocks, FirstPointsAreTheSobolSequence) {
  // Index order (not Gray-code order): dimension 0 is the van der Corput sequence.
  const float dim0[] = {0.0f, 0.5f, 0.25f, 0.75f, 0.125f, 0.625f, 0.375f, 0.875f};
  const float dim1[] = {0.0f, 0.5f, 0.75f, 0.25f, 0.625f, 0.125f, 0.375f, 0.875f};
  for (uint32_t i = 0; i < 8; ++i) {
    EXPECT_EQ(float(sobol_dim0(i)) * 0x1p-32f, dim0[i]) << i;
    EXPECT_EQ(float(sobol_dim1(i)) * 0x1p-32f, dim1[i]) << i;
  }
}

TEST(SobolBuildingBlocks, UnscrambledPrefixesAreNets) {
  std::vector<Vec2> points;
  for (uint32_t i = 0; i < 1024; ++i)
    points.push_back({float(sobol_dim0(i)) * 0x1p-32f, float(sobol_dim1(i)) * 0x1p-32f});
  expect_0m2_net(points, 10);
}

// Owen scrambling permutes digits depending only on more significant digits, so values that agree
// in their top k bits still agree in their top k bits after scrambling, and it is a bijection.
TEST(SobolBuildingBlocks, ScrambleIsNestedBijection) {
  for (uint32_t seed : {0u, 1u, 0xdeadbeefu}) {
    std::set<uint32_t> images;
    for (uint32_t x = 0; x < 4096; ++x) images.insert(nested_uniform_scramble(x << 20, seed) >> 20);
    EXPECT_EQ(images.size(), 4096u);
    for (uint32_t x = 0; x < 1000; ++x) {
      const uint32_t a = x * 2654435761u, b = a ^ (x & 0xffffu);  // share the top 16 bits
      EXPECT_EQ(nested_uniform_scramble(a, seed) >> 16, nested_uniform_scramble(b, seed) >> 16);
    }
  }
  EXPECT_NE(nested_uniform_scramble(0, 1), nested_uniform_scramble(0, 2));
}

TEST(Sampler, ValuesInUnitInterval) {
  for (uint64_t seed : {0ull, 42ull})
    for (int y = 0; y < 8; ++y)
      for (int x = -4; x < 8; ++x)
        for (uint32_t i : {0u, 1u, 7u, 255u, 0xffffffffu})
          for (uint32_t d = 0; d < 12; ++d) {
            const Sampler s(seed, {x, y}, i);
            const float v = s.get_1d(d);
            const Vec2 p = s.get_2d(d);
            ASSERT_GE(v, 0.0f);
            ASSERT_LT(v, 1.0f);
            ASSERT_GE(p.x, 0.0f);
            ASSERT_LT(p.x, 1.0f);
            ASSERT_GE(p.y, 0.0f);
            ASSERT_LT(p.y, 1.0f);
          }
}

TEST(Sampler, Deterministic) {
  for (uint32_t i = 0; i < 64; ++i) {
    const Sampler a(9, {3, 5}, i), b(9, {3, 5}, i);
    EXPECT_EQ(a.get_1d(4), b.get_1d(4));
    EXPECT_EQ(a.get_2d(7).x, b.get_2d(7).x);
    EXPECT_EQ(a.get_2d(7).y, b.get_2d(7).y);
  }
  EXPECT_EQ(Sampler(9, {3, 5}, 17).sample_index(), 17u);
  EXPECT_EQ(Sampler(9, {3, 5}, 17).pixel(), (Vec2i{3, 5}));
}

TEST(Sampler, PixelsDimensionsAndSeedsDiffer) {
  const auto sequence = [](uint64_t seed, Vec2i pixel, uint32_t dim) {
    return pixel_values_1d(seed, pixel, dim, 16);
  };
  const std::vector<float> base = sequence(1, {0, 0}, 0);
  EXPECT_NE(base, sequence(1, {1, 0}, 0));
  EXPECT_NE(base, sequence(1, {0, 1}, 0));
  EXPECT_NE(sequence(1, {1, 0}, 0), sequence(1, {0, 1}, 0));  // x and y are not interchangeable
  EXPECT_NE(base, sequence(1, {0, 0}, 1));
  EXPECT_NE(base, sequence(2, {0, 0}, 0));
  // The two coordinates of one 2D sample differ too.
  int equal = 0;
  for (uint32_t i = 0; i < 64; ++i) {
    const Vec2 p = Sampler(1, {0, 0}, i).get_2d(0);
    equal += p.x == p.y;
  }
  EXPECT_EQ(equal, 0);
}

TEST(Sampler, OneDimensionalValuesAreStratified) {
  constexpr uint32_t kN = 256;
  for (uint64_t seed : {0ull, 5ull})
    for (Vec2i pixel : {Vec2i{0, 0}, Vec2i{17, 3}, Vec2i{-2, 100}})
      for (uint32_t dim : {0u, 1u, 6u, 31u}) {
        std::vector<int> count(kN, 0);
        for (float v : pixel_values_1d(seed, pixel, dim, kN)) ++count[size_t(v * kN)];
        for (int c : count) ASSERT_EQ(c, 1) << "seed " << seed << " dim " << dim;
      }
}

TEST(Sampler, TwoDimensionalValuesFormNets) {
  for (uint64_t seed : {0ull, 5ull})
    for (Vec2i pixel : {Vec2i{0, 0}, Vec2i{17, 3}, Vec2i{-2, 100}})
      for (uint32_t dim : {0u, 1u, 6u, 31u}) {
        SCOPED_TRACE(testing::Message()
                     << "seed " << seed << " pixel " << pixel.x << "," << pixel.y << " dim " << dim);
        expect_0m2_net(pixel_points_2d(seed, pixel, dim, 0, 256), 8);
        // Progressive rendering: every power-of-two prefix, and later aligned blocks, are nets too.
        expect_0m2_net(pixel_points_2d(seed, pixel, dim, 0, 16), 4);
        expect_0m2_net(pixel_points_2d(seed, pixel, dim, 256, 256), 8);
      }
}

TEST(Sampler, LowCorrelationAcrossPixelsAndDimensions) {
  // For independent uniforms E[x y] = 1/4 with standard deviation sqrt(7/144) per product; over
  // 4096 pixels that is 0.0034, so 0.015 is a >4 sigma tolerance.
  double xy = 0.0, d01 = 0.0, d25 = 0.0, mean_x = 0.0;
  int n = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x, ++n) {
      const Sampler s(3, {x, y}, 0);
      const Vec2 p = s.get_2d(sample_dim::kFilm);
      xy += p.x * p.y;
      mean_x += p.x;
      d01 += s.get_1d(0) * s.get_1d(1);
      d25 += s.get_1d(2) * s.get_1d(5);
    }
  EXPECT_NEAR(xy / n, 0.25, 0.015);
  EXPECT_NEAR(d01 / n, 0.25, 0.015);
  EXPECT_NEAR(d25 / n, 0.25, 0.015);
  EXPECT_NEAR(mean_x / n, 0.5, 0.02);
}

TEST(Sampler, LowCorrelationBetweenDimensionsWithinPixel) {
  // Across the samples of one pixel, dimensions are shuffled independently.
  constexpr uint32_t kN = 1024;
  for (uint32_t d = 0; d < 8; ++d) {
    double sum = 0.0;
    for (uint32_t i = 0; i < kN; ++i) {
      const Sampler s(11, {5, 9}, i);
      sum += s.get_1d(d) * s.get_1d(d + 1);
    }
    EXPECT_NEAR(sum / kN, 0.25, 0.03) << "dimensions " << d << " and " << d + 1;
  }
}

TEST(SampleDim, NamedDimensionsDoNotCollide) {
  std::set<uint32_t> used = {sample_dim::kFilm, sample_dim::kLens};
  for (int depth = 0; depth < 16; ++depth)
    for (uint32_t which = 0; which < sample_dim::kPerBounce; ++which)
      EXPECT_TRUE(used.insert(sample_dim::bounce(depth, sample_dim::Bounce(which))).second);
}

}  // namespace caligo
