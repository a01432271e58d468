#include "image/compare.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace caligo {
namespace {

// A small image with varied values, so that sums and maxima are not trivially right.
Image gradient(int width, int height, std::vector<std::string> channels = {"R", "G", "B"}) {
  Image image(width, height, std::move(channels));
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < image.channel_count(); ++c) image.at(x, y, c) = 0.1f * x + 0.3f * y + 0.05f * c;
  return image;
}

TEST(Compare, IdenticalImagesGiveZeros) {
  Image a = gradient(5, 4);
  ImageMetrics m = compare_images(a, a);
  EXPECT_EQ(m.rmse, 0.0);
  EXPECT_EQ(m.relative_mse, 0.0);
  EXPECT_EQ(m.mean_difference, 0.0);
  EXPECT_EQ(m.max_abs_difference, 0.0);
  EXPECT_EQ(m.pixels, 20u);
}

TEST(Compare, ConstantOffsetGivesTheOffset) {
  const float d = 0.25f;
  Image reference = gradient(5, 4);
  Image shifted = reference;
  for (float& v : shifted.pixels()) v += d;
  ImageMetrics m = compare_images(shifted, reference);
  EXPECT_NEAR(m.rmse, d, 1e-6);
  EXPECT_NEAR(m.mean_difference, d, 1e-6);
  EXPECT_NEAR(m.max_abs_difference, d, 1e-6);
  // Darker test image: the sign of mean_difference says which way the bias goes.
  EXPECT_NEAR(compare_images(reference, shifted).mean_difference, -d, 1e-6);
}

TEST(Compare, RelativeMseDividesByTheReference) {
  Image a(1, 1, {"R", "G", "B"}), b(1, 1, {"R", "G", "B"});
  a.set_rgb(0, 0, 0, RGB(2.0f, 0.0f, 1.0f));
  b.set_rgb(0, 0, 0, RGB(1.0f, 0.0f, 0.0f));
  // Channels: (1)^2/(1 + 0.01), 0, (1)^2/(0 + 0.01).
  double expected = (1.0 / 1.01 + 0.0 + 1.0 / 0.01) / 3.0;
  EXPECT_NEAR(compare_images(a, b).relative_mse, expected, 1e-9);
  double swapped = (1.0 / 4.01 + 0.0 + 1.0 / 1.01) / 3.0;
  EXPECT_NEAR(compare_images(b, a).relative_mse, swapped, 1e-9);
}

TEST(Compare, MaxAbsAndRmseOfASingleDifference) {
  Image a = gradient(4, 4), b = gradient(4, 4);
  a.at(2, 3, 1) += 3.0f;
  ImageMetrics m = compare_images(a, b);
  EXPECT_NEAR(m.max_abs_difference, 3.0, 1e-6);
  EXPECT_NEAR(m.rmse, std::sqrt(9.0 / 48.0), 1e-6);
  EXPECT_NEAR(m.mean_difference, 3.0 / 48.0, 1e-6);
}

TEST(Compare, OnlyRgbCountsAndChannelOrderDoesNot) {
  Image a = gradient(3, 3, {"R", "G", "B", "Z"});
  Image b(3, 3, {"Z", "B", "G", "R"});
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 3; ++x) {
      b.at(x, y, 3) = a.at(x, y, 0);
      b.at(x, y, 2) = a.at(x, y, 1);
      b.at(x, y, 1) = a.at(x, y, 2);
      b.at(x, y, 0) = 1000.0f;
    }
  ImageMetrics m = compare_images(a, b);
  EXPECT_EQ(m.rmse, 0.0);
  EXPECT_EQ(m.max_abs_difference, 0.0);
}

TEST(Compare, NonFiniteValuesAreNotHidden) {
  Image a = gradient(3, 1), b = gradient(3, 1);
  a.at(0, 0, 0) = std::numeric_limits<float>::quiet_NaN();
  ImageMetrics m = compare_images(a, b);
  EXPECT_TRUE(std::isnan(m.rmse));
  EXPECT_TRUE(std::isnan(m.max_abs_difference));
}

TEST(Compare, SizeMismatchThrowsAndSaysSo) {
  try {
    compare_images(gradient(4, 3), gradient(3, 4));
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("4x3"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("3x4"), std::string::npos) << e.what();
  }
}

TEST(Compare, MissingRgbThrows) {
  EXPECT_THROW(compare_images(gradient(2, 2, {"R", "G", "Z"}), gradient(2, 2)), std::invalid_argument);
  EXPECT_THROW(compare_images(gradient(2, 2), gradient(2, 2, {"Y"})), std::invalid_argument);
}

TEST(Compare, EmptyImagesCompareAsIdentical) {
  ImageMetrics m = compare_images(Image(0, 0, {"R", "G", "B"}), Image(0, 0, {"R", "G", "B"}));
  EXPECT_EQ(m.pixels, 0u);
  EXPECT_EQ(m.rmse, 0.0);
}

}  // namespace
}  // namespace caligo
