// The PNG preview through libpng, read back by OpenImageIO (an independent decoder): bytes
// written are the bytes read back, atomically. (This binary links OpenImageIO; others do not.)
#include "image/png_io.h"

#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <filesystem>

namespace caligo {
namespace {

namespace fs = std::filesystem;

TEST(PngIo, RoundTripsEightBitRgb) {
  const fs::path dir = fs::temp_directory_path() / ("caligo-png-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path path = dir / "preview.png";
  const int w = 5, h = 3;
  std::vector<uint8_t> rgb(size_t(w * h * 3));
  for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = uint8_t(i * 17 % 256);
  write_png(path.string(), w, h, rgb);

  auto in = OIIO::ImageInput::open(path.string());
  ASSERT_TRUE(in) << OIIO::geterror();
  const OIIO::ImageSpec& spec = in->spec();
  EXPECT_EQ(spec.width, w);
  EXPECT_EQ(spec.height, h);
  EXPECT_EQ(spec.nchannels, 3);
  std::vector<uint8_t> back(rgb.size());
  ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, back.data()));
  in->close();
  EXPECT_EQ(back, rgb);
  // Nothing but the file itself is left in the directory (no temporary).
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);
  fs::remove_all(dir);
}

TEST(PngIo, MissingDirectoryThrowsAndWritesNothing) {
  const fs::path path = fs::temp_directory_path() / "caligo-no-such-dir" / "x.png";
  EXPECT_ANY_THROW(write_png(path.string(), 1, 1, {0, 0, 0}));
  EXPECT_FALSE(fs::exists(path));
}

TEST(PngIo, WrongBufferSizeIsRejected) {
  EXPECT_THROW(write_png((fs::temp_directory_path() / "caligo-bad.png").string(), 2, 2, {1, 2, 3}),
               std::invalid_argument);
}

}  // namespace
}  // namespace caligo
