// Tests of the procedural gobos (gobo_generate.h): determinism, the look each pattern
// promises (panes of several hues with dark leading, bar columns, a half-grey checker) and
// values that are finite and within [0, 1].
#include "lights/gobo_generate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

namespace caligo {
namespace {

bool same_pixels(const GoboImage& a, const GoboImage& b) {
  if (a.width() != b.width() || a.height() != b.height()) return false;
  return std::equal(a.data(), a.data() + a.width() * a.height(), b.data());
}

// Hue in degrees of a clearly coloured pixel, rounded to 10-degree bins.
int hue_bin(RGB c) {
  const float hi = c.max_component(), lo = std::min({c.r, c.g, c.b});
  const float d = hi - lo;
  float h = hi == c.r   ? std::fmod((c.g - c.b) / d, 6.0f)
            : hi == c.g ? (c.b - c.r) / d + 2.0f
                        : (c.r - c.g) / d + 4.0f;
  if (h < 0.0f) h += 6.0f;
  return int(h * 60.0f) / 10;
}

TEST(GoboGenerate, ParsesThePatternNames) {
  EXPECT_EQ(parse_gobo_pattern("stained_glass"), GoboPattern::kStainedGlass);
  EXPECT_EQ(parse_gobo_pattern("bars"), GoboPattern::kBars);
  EXPECT_EQ(parse_gobo_pattern("checker"), GoboPattern::kChecker);
  EXPECT_FALSE(parse_gobo_pattern("Checker"));
}

TEST(GoboGenerate, EveryValueIsFiniteAndInTheUnitInterval) {
  for (GoboPattern kind : {GoboPattern::kStainedGlass, GoboPattern::kBars, GoboPattern::kChecker})
    for (int res : {8, 37, 256}) {
      const GoboImage image = generate_gobo(kind, res, 5);
      ASSERT_EQ(image.width(), res);
      ASSERT_EQ(image.height(), res);
      for (int i = 0; i < res * res; ++i) {
        const RGB c = image.data()[i];
        ASSERT_TRUE(c.is_finite());
        for (int k = 0; k < 3; ++k) ASSERT_TRUE(c[k] >= 0.0f && c[k] <= 1.0f) << c[k];
      }
    }
}

TEST(GoboGenerate, RejectsResolutionsOutOfRange) {
  EXPECT_THROW(generate_gobo(GoboPattern::kBars, 7, 1), std::invalid_argument);
  EXPECT_THROW(generate_gobo(GoboPattern::kBars, 4097, 1), std::invalid_argument);
}

TEST(GoboGenerate, StainedGlassIsDeterministicPerSeedAndDiffersAcrossSeeds) {
  const GoboImage a = generate_gobo(GoboPattern::kStainedGlass, 64, 7);
  EXPECT_TRUE(same_pixels(a, generate_gobo(GoboPattern::kStainedGlass, 64, 7)));
  EXPECT_FALSE(same_pixels(a, generate_gobo(GoboPattern::kStainedGlass, 64, 8)));
  EXPECT_FALSE(same_pixels(a, generate_gobo(GoboPattern::kStainedGlass, 64, 0)));
}

TEST(GoboGenerate, StainedGlassHasColouredPanesDarkLeadingAndADarkRim) {
  for (uint32_t seed : {0u, 1u, 2u, 12345u}) {
    SCOPED_TRACE(seed);
    const int n = 256;
    const GoboImage image = generate_gobo(GoboPattern::kStainedGlass, n, seed);
    std::set<int> hues;
    int dark = 0, bright = 0;
    for (int i = 0; i < n * n; ++i) {
      const RGB c = image.data()[i];
      if (c.max_component() < 0.05f) ++dark;
      if (c.luminance() > 0.2f) {
        ++bright;
        // Panes are saturated and of about equal luminance.
        EXPECT_GT(c.max_component() - std::min({c.r, c.g, c.b}), 0.2f);
        EXPECT_NEAR(c.luminance(), 0.3f, 0.02f);
        hues.insert(hue_bin(c));
      }
    }
    EXPECT_GE(hues.size(), 3u);
    // Leading plus the corners outside the rim (1 - pi 0.48^2 = 28% of the image).
    EXPECT_GT(dark, n * n / 4);
    EXPECT_GT(bright, n * n / 2);
    EXPECT_EQ(dark + bright, n * n);
    // The corners and the ring just outside radius 0.48 are lead; the centre region is mostly glass.
    EXPECT_LT(image.pixel(0, 0).max_component(), 0.05f);
    EXPECT_LT(image.pixel(n / 2, 2).max_component(), 0.05f);
    EXPECT_LT(image.pixel(n - 3, n / 2).max_component(), 0.05f);
  }
}

TEST(GoboGenerate, BarsAreEightWhiteColumnsOnBlack) {
  const int n = 256;
  const GoboImage image = generate_gobo(GoboPattern::kBars, n, 1);
  for (int x = 0; x < n; ++x) {
    const float expected = (x / (n / 16)) % 2 == 0 ? 1.0f : 0.0f;  // white, black, white, ...
    for (int y = 0; y < n; ++y) ASSERT_EQ(image.pixel(x, y), RGB(expected)) << x << ", " << y;
  }
  // The seed does not matter; an odd resolution grey-blends the texels that straddle an edge.
  EXPECT_TRUE(same_pixels(image, generate_gobo(GoboPattern::kBars, n, 99)));
  const GoboImage odd = generate_gobo(GoboPattern::kBars, 24, 1);  // 3 texels per stripe
  EXPECT_FLOAT_EQ(odd.pixel(1, 5).r, 0.5f);
  EXPECT_NEAR(odd.mean().r, 0.5f, 1e-6f);
}

TEST(GoboGenerate, CheckerIsEightByEightWithMeanOneHalf) {
  for (int n : {8, 16, 64, 100, 256}) {
    SCOPED_TRACE(n);
    const GoboImage image = generate_gobo(GoboPattern::kChecker, n, 1);
    EXPECT_NEAR(image.mean().r, 0.5f, 1e-6f);
    EXPECT_EQ(image.mean().r, image.mean().g);
  }
  const int n = 64, cell = n / 8;
  const GoboImage image = generate_gobo(GoboPattern::kChecker, n, 1);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      ASSERT_EQ(image.pixel(x, y).r, (x / cell + y / cell) % 2 == 0 ? 1.0f : 0.0f) << x << ", " << y;
}

}  // namespace
}  // namespace caligo
