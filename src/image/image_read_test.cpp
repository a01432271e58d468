// Reading pictures as linear RGB through OpenImageIO (gobo textures).
#include "image/image_read.h"

#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "image/png_io.h"

namespace caligo {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir() {
  const fs::path dir = fs::temp_directory_path() / ("caligo-read-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

TEST(SrgbToLinear, KnownValues) {
  EXPECT_FLOAT_EQ(srgb_to_linear(0.0f), 0.0f);
  EXPECT_FLOAT_EQ(srgb_to_linear(1.0f), 1.0f);
  EXPECT_NEAR(srgb_to_linear(0.5f), 0.21404f, 1e-5f);               // the standard's mid grey
  EXPECT_NEAR(srgb_to_linear(0.04045f), 0.04045f / 12.92f, 1e-7f);  // the linear segment's end
}

TEST(ReadImageRgb, EightBitPngIsSrgbDecoded) {
  const fs::path path = temp_dir() / "gobo.png";
  const int w = 3, h = 2;
  std::vector<uint8_t> rgb(size_t(w * h * 3));
  for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = uint8_t(i * 40 % 256);
  write_png(path.string(), w, h, rgb);
  const Image image = read_image_rgb(path.string());
  ASSERT_EQ(image.width(), w);
  ASSERT_EQ(image.height(), h);
  ASSERT_EQ(image.channel_count(), 3);
  for (size_t i = 0; i < rgb.size(); ++i)
    EXPECT_NEAR(image.pixels()[i], srgb_to_linear(rgb[i] / 255.0f), 1e-6f) << i;
  fs::remove_all(path.parent_path());
}

TEST(ReadImageRgb, GreyBecomesRgb) {
  const fs::path path = temp_dir() / "grey.png";
  auto out = OIIO::ImageOutput::create("png");
  ASSERT_TRUE(out);
  const uint8_t grey[2] = {0, 255};
  ASSERT_TRUE(out->open(path.string(), OIIO::ImageSpec(2, 1, 1, OIIO::TypeDesc::UINT8)));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, grey));
  ASSERT_TRUE(out->close());
  const Image image = read_image_rgb(path.string());
  ASSERT_EQ(image.width(), 2);
  for (int c = 0; c < 3; ++c) {
    EXPECT_FLOAT_EQ(image.pixels()[size_t(c)], 0.0f);
    EXPECT_FLOAT_EQ(image.pixels()[size_t(3 + c)], 1.0f);
  }
  fs::remove_all(path.parent_path());
}

TEST(ReadImageRgb, MissingAndBrokenFilesAreInputErrorsNamingTheFile) {
  const fs::path dir = temp_dir();
  try {
    read_image_rgb((dir / "none.png").string());
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, (dir / "none.png").string());
  }
  const fs::path broken = dir / "broken.png";
  std::ofstream(broken) << "this is not a picture";
  try {
    read_image_rgb(broken.string());
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("broken.png"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace caligo
