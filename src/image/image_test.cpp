#include "image/image.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace caligo {
namespace {

TEST(Image, StartsZeroFilledWithGivenChannels) {
  Image image(3, 2, {"R", "G", "B", "Z"});
  EXPECT_EQ(image.width(), 3);
  EXPECT_EQ(image.height(), 2);
  EXPECT_EQ(image.pixel_count(), 6u);
  EXPECT_EQ(image.channel_count(), 4);
  EXPECT_EQ(image.pixels().size(), 24u);
  for (float v : image.pixels()) EXPECT_EQ(v, 0.0f);
}

TEST(Image, ChannelIndexFindsNamesAndReportsAbsence) {
  Image image(1, 1, {"R", "G", "B", "N.X", "albedo.R"});
  EXPECT_EQ(image.channel_index("R"), 0);
  EXPECT_EQ(image.channel_index("N.X"), 3);
  EXPECT_EQ(image.channel_index("albedo.R"), 4);
  EXPECT_EQ(image.channel_index("A"), -1);
  EXPECT_EQ(image.channel_index("r"), -1);  // names are case-sensitive, as in EXR
  EXPECT_TRUE(image.has_channel("G"));
  EXPECT_FALSE(image.has_channel(""));
}

TEST(Image, AtAddressesEachSampleSeparately) {
  Image image(4, 3, {"R", "G"});
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x)
      for (int c = 0; c < 2; ++c) image.at(x, y, c) = float(100 * y + 10 * x + c);
  const Image& view = image;
  EXPECT_EQ(view.at(0, 0, 0), 0.0f);
  EXPECT_EQ(view.at(3, 2, 1), 231.0f);
  EXPECT_EQ(view.at(1, 2, 0), 210.0f);
}

TEST(Image, StoresChannelsInterleavedRowMajor) {
  Image image(2, 2, {"R", "G", "B"});
  image.at(1, 0, 2) = 5.0f;
  image.at(0, 1, 0) = 7.0f;
  EXPECT_EQ(image.pixels()[(0 * 2 + 1) * 3 + 2], 5.0f);
  EXPECT_EQ(image.pixels()[(1 * 2 + 0) * 3 + 0], 7.0f);
}

TEST(Image, RgbReadsAndWritesThreeChannelsFromABase) {
  Image image(2, 1, {"Z", "albedo.R", "albedo.G", "albedo.B"});
  image.set_rgb(1, 0, 1, RGB(0.25f, 0.5f, 0.75f));
  EXPECT_EQ(image.rgb(1, 0, 1), RGB(0.25f, 0.5f, 0.75f));
  EXPECT_EQ(image.at(1, 0, 0), 0.0f);
  EXPECT_EQ(image.rgb(0, 0, 1), RGB(0.0f));
}

TEST(Image, RgbIndicesFindsScatteredChannelsOrNothing) {
  Image image(1, 1, {"B", "Z", "G", "R", "albedo.R", "albedo.G"});
  ASSERT_TRUE(image.rgb_indices().has_value());
  EXPECT_EQ(*image.rgb_indices(), (std::array<int, 3>{3, 2, 0}));
  EXPECT_FALSE(image.rgb_indices("albedo.").has_value());
  image.at(0, 0, 3) = 1.0f;
  image.at(0, 0, 0) = 3.0f;
  EXPECT_EQ(image.rgb(0, 0, *image.rgb_indices()), RGB(1.0f, 0.0f, 3.0f));
}

TEST(Image, IsAValueType) {
  Image a(2, 2, {"R"});
  Image b = a;
  EXPECT_EQ(a, b);
  b.at(1, 1, 0) = 1.0f;
  EXPECT_NE(a, b);
  EXPECT_EQ(a.at(1, 1, 0), 0.0f);
}

TEST(Image, EmptyImagesAreAllowed) {
  Image image(0, 5, {"R"});
  EXPECT_EQ(image.pixel_count(), 0u);
  EXPECT_TRUE(image.pixels().empty());
  EXPECT_EQ(Image().channel_count(), 0);
}

TEST(Image, RejectsBadSizesAndChannelNames) {
  EXPECT_THROW(Image(-1, 2, {"R"}), std::invalid_argument);
  EXPECT_THROW(Image(2, 2, {"R", ""}), std::invalid_argument);
  EXPECT_THROW(Image(2, 2, {"R", "G", "R"}), std::invalid_argument);
}

}  // namespace
}  // namespace caligo
