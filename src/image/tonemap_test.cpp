#include "image/tonemap.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace caligo {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

TEST(Tonemap, ExposureIsPowerOfTwo) {
  EXPECT_FLOAT_EQ(exposure_scale(0.0f), 1.0f);
  EXPECT_FLOAT_EQ(exposure_scale(1.0f), 2.0f);
  EXPECT_FLOAT_EQ(exposure_scale(-2.0f), 0.25f);
}

TEST(Tonemap, FilmicCurveMapsZeroToZero) {
  EXPECT_EQ(aces_filmic(0.0f), 0.0f);
  EXPECT_EQ(aces_filmic(-3.0f), 0.0f);
}

TEST(Tonemap, FilmicCurveIsMonotoneAndSaturatesAtOne) {
  float previous = aces_filmic(0.0f);
  for (float x = 1e-4f; x < 100.0f; x *= 1.05f) {
    float y = aces_filmic(x);
    if (x < 7.0f) {
      EXPECT_GT(y, previous) << "x = " << x;  // strictly increasing below the clamp
    } else {
      EXPECT_GE(y, previous) << "x = " << x;
    }
    EXPECT_LE(y, 1.0f);
    previous = y;
  }
  EXPECT_EQ(aces_filmic(8.0f), 1.0f);
  EXPECT_EQ(aces_filmic(kInf), 1.0f);
  EXPECT_EQ(aces_filmic(kNaN), 0.0f);
}

TEST(Tonemap, FilmicCurveMatchesTheFormulaAtMidGrey) {
  double x = 0.18;
  double expected = x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14);
  EXPECT_NEAR(aces_filmic(0.18f), expected, 1e-6);
}

TEST(Tonemap, SrgbOetfKnownValues) {
  EXPECT_EQ(srgb_oetf(0.0f), 0.0f);
  EXPECT_NEAR(srgb_oetf(1.0f), 1.0f, 1e-6);
  EXPECT_NEAR(srgb_oetf(0.5f), 0.735357, 1e-5);
  EXPECT_NEAR(srgb_oetf(0.18f), 0.461356, 1e-5);
  EXPECT_NEAR(srgb_oetf(0.001f), 0.01292f, 1e-7);  // linear segment
  // The two pieces meet at 0.0031308 (both give ~0.040450).
  EXPECT_NEAR(srgb_oetf(0.0031308f), 0.0404500, 1e-6);
  EXPECT_NEAR(srgb_oetf(std::nextafter(0.0031308f, 1.0f)), 0.0404500, 1e-6);
}

TEST(Tonemap, QuantisationRoundsAndClamps) {
  EXPECT_EQ(quantize_unorm8(0.0f), 0);
  EXPECT_EQ(quantize_unorm8(1.0f), 255);
  EXPECT_EQ(quantize_unorm8(0.5f), 128);  // 127.5 rounds up
  EXPECT_EQ(quantize_unorm8(0.499f / 255.0f), 0);
  EXPECT_EQ(quantize_unorm8(0.501f / 255.0f), 1);
  EXPECT_EQ(quantize_unorm8(-1.0f), 0);
  EXPECT_EQ(quantize_unorm8(2.0f), 255);
  EXPECT_EQ(quantize_unorm8(kNaN), 0);
}

TEST(Tonemap, WithoutFilmicOneMapsToWhite) {
  PreviewSettings linear{.exposure_stops = 0.0f, .filmic = false};
  EXPECT_EQ(preview_channel(1.0f, linear), 255);
  EXPECT_EQ(preview_channel(4.0f, linear), 255);
  EXPECT_EQ(preview_channel(0.5f, linear), 188);  // round(0.735357 * 255)
}

TEST(Tonemap, ExposurePlusOneDoublesInputBeforeTheCurve) {
  for (bool filmic : {true, false}) {
    PreviewSettings plain{.exposure_stops = 0.0f, .filmic = filmic};
    PreviewSettings brighter{.exposure_stops = 1.0f, .filmic = filmic};
    for (float v : {0.01f, 0.1f, 0.2f, 0.45f, 1.3f}) {
      EXPECT_EQ(preview_channel(v, brighter), preview_channel(2.0f * v, plain)) << v;
    }
  }
  PreviewSettings brighter{.exposure_stops = 1.0f, .filmic = true};
  EXPECT_EQ(preview_channel(0.1f, brighter), quantize_unorm8(srgb_oetf(aces_filmic(0.2f))));
}

Image rgb_image(int width, int height) { return Image(width, height, {"R", "G", "B"}); }

TEST(Tonemap, PreviewIsThreeBytesPerPixelInRowOrder) {
  Image image = rgb_image(2, 2);
  image.set_rgb(1, 0, 0, RGB(1.0f, 0.0f, 0.5f));
  std::vector<uint8_t> bytes = to_srgb8_preview(image, {.exposure_stops = 0.0f, .filmic = false});
  ASSERT_EQ(bytes.size(), 12u);
  EXPECT_EQ(bytes[3], 255);
  EXPECT_EQ(bytes[4], 0);
  EXPECT_EQ(bytes[5], 188);
  for (size_t i : {0u, 1u, 2u, 6u, 7u, 8u, 9u, 10u, 11u}) EXPECT_EQ(bytes[i], 0) << i;
}

TEST(Tonemap, PreviewReadsRgbByNameNotPosition) {
  Image image(1, 1, {"Z", "B", "G", "R"});
  image.at(0, 0, 3) = 1.0f;  // R
  image.at(0, 0, 0) = 1.0f;  // Z: must be ignored
  std::vector<uint8_t> bytes = to_srgb8_preview(image, {.exposure_stops = 0.0f, .filmic = false});
  EXPECT_EQ(bytes, (std::vector<uint8_t>{255, 0, 0}));
}

TEST(Tonemap, PreviewMapsNonFiniteToBlackAndCountsPixels) {
  Image image = rgb_image(3, 1);
  image.set_rgb(0, 0, 0, RGB(kNaN, 0.5f, 0.5f));
  image.set_rgb(1, 0, 0, RGB(kInf, -kInf, kNaN));
  image.set_rgb(2, 0, 0, RGB(0.5f));
  size_t non_finite = 99;
  std::vector<uint8_t> bytes = to_srgb8_preview(image, {}, &non_finite);
  EXPECT_EQ(non_finite, 2u);
  EXPECT_EQ(bytes[0], 0);
  EXPECT_EQ(bytes[1], preview_channel(0.5f, {}));
  EXPECT_EQ(bytes[3], 0);
  EXPECT_EQ(bytes[4], 0);
  EXPECT_EQ(bytes[5], 0);
  EXPECT_GT(bytes[6], 0);
}

TEST(Tonemap, HugeExposureDoesNotProduceGarbage) {
  Image image = rgb_image(1, 1);
  image.set_rgb(0, 0, 0, RGB(0.0f, 1e-30f, 3e38f));
  size_t non_finite = 99;
  std::vector<uint8_t> bytes = to_srgb8_preview(image, {.exposure_stops = 200.0f}, &non_finite);
  EXPECT_EQ(non_finite, 0u);
  EXPECT_EQ(bytes[2], 255);
  EXPECT_EQ(bytes[0], 0);  // 0 * 2^200 = 0 * Inf would be NaN
}

TEST(Tonemap, PreviewNeedsRgb) {
  EXPECT_THROW(to_srgb8_preview(Image(1, 1, {"R", "G", "Z"})), std::invalid_argument);
}

}  // namespace
}  // namespace caligo
