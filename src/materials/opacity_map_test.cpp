#include "materials/opacity_map.h"

#include <gtest/gtest.h>

namespace caligo {
namespace {

// A 2x2 map: top row 0, 1; bottom row 0.5, 0.25 (rows top to bottom, v up).
OpacityMap two_by_two() { return OpacityMap(2, 2, {0.0f, 1.0f, 0.5f, 0.25f}); }

TEST(OpacityMap, TexelCentresReturnTheirValues) {
  const OpacityMap m = two_by_two();
  EXPECT_FLOAT_EQ(m.lookup({0.25f, 0.75f}), 0.0f);
  EXPECT_FLOAT_EQ(m.lookup({0.75f, 0.75f}), 1.0f);
  EXPECT_FLOAT_EQ(m.lookup({0.25f, 0.25f}), 0.5f);
  EXPECT_FLOAT_EQ(m.lookup({0.75f, 0.25f}), 0.25f);
}

TEST(OpacityMap, InterpolatesBilinearlyAndRepeats) {
  const OpacityMap m = two_by_two();
  // Midway between the top two texel centres.
  EXPECT_FLOAT_EQ(m.lookup({0.5f, 0.75f}), 0.5f);
  // The centre of the map: the mean of all four.
  EXPECT_FLOAT_EQ(m.lookup({0.5f, 0.5f}), (0.0f + 1.0f + 0.5f + 0.25f) / 4.0f);
  // One period away reads the same texel; u = 0 lies halfway between the last and first column.
  EXPECT_FLOAT_EQ(m.lookup({1.25f, -0.25f}), m.lookup({0.25f, 0.75f}));
  EXPECT_FLOAT_EQ(m.lookup({-0.75f, 1.25f}), 0.5f);
  EXPECT_FLOAT_EQ(m.lookup({0.0f, 0.75f}), 0.5f);
}

TEST(OpacityMap, ValuesAreClampedAndSizesChecked) {
  const OpacityMap m(1, 1, {7.0f});
  EXPECT_FLOAT_EQ(m.lookup({0.3f, 0.3f}), 1.0f);
  EXPECT_THROW(OpacityMap(2, 2, {0.0f}), std::invalid_argument);
}

}  // namespace
}  // namespace caligo
