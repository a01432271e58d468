#include "image/exr_io.h"

#include <ImfChannelList.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfMatrixAttribute.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/error.h"

namespace caligo {
namespace {

namespace fs = std::filesystem;

// Every test gets its own empty directory, removed afterwards.
class ExrIo : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = "caligo_exr_io_test_" + std::to_string(getpid()) + "_" + info->name();
    dir_ = fs::temp_directory_path() / name;
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string file(const std::string& name) const { return (dir_ / name).string(); }
  size_t files_in_dir() const { return size_t(std::distance(fs::directory_iterator(dir_), {})); }

  fs::path dir_;
};

const std::vector<std::string> kAovChannels = {"R",   "G",   "B",        "A",        "Z",       "N.X",
                                               "N.Y", "N.Z", "albedo.R", "albedo.G", "albedo.B"};

// Distinct, awkward values everywhere: fractions with full mantissas, negatives, large values.
Image test_image(int width, int height, const std::vector<std::string>& channels) {
  Image image(width, height, channels);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < image.channel_count(); ++c)
        image.at(x, y, c) = std::sin(1.7f * x + 2.3f * y + 0.61f * c) * std::exp2(float(c % 7) - 3.0f);
  return image;
}

void expect_bit_identical(const Image& actual, const Image& expected) {
  ASSERT_EQ(actual.width(), expected.width());
  ASSERT_EQ(actual.height(), expected.height());
  ASSERT_EQ(actual.channels(), expected.channels());
  for (size_t i = 0; i < expected.pixels().size(); ++i) {
    ASSERT_EQ(std::bit_cast<uint32_t>(actual.pixels()[i]), std::bit_cast<uint32_t>(expected.pixels()[i]))
        << "sample " << i << ": " << actual.pixels()[i] << " vs " << expected.pixels()[i];
  }
}

TEST_F(ExrIo, FloatRoundTripIsBitIdenticalForEveryChannel) {
  Image image = test_image(7, 5, kAovChannels);
  image.at(0, 0, 0) = std::numeric_limits<float>::quiet_NaN();
  image.at(1, 0, 0) = std::numeric_limits<float>::infinity();
  image.at(2, 0, 0) = -0.0f;
  image.at(3, 0, 0) = std::numeric_limits<float>::denorm_min();
  image.at(4, 0, 0) = std::numeric_limits<float>::max();
  write_exr(file("aov.exr"), image);
  // The channel order a renderer writes comes back, although EXR stores names sorted.
  expect_bit_identical(read_exr(file("aov.exr")), image);
}

// Header attributes come back as written: text, integers, floats, and matrices element for
// element (stored transposed, as Imath's row-vector M44f, and transposed back).
TEST_F(ExrIo, HeaderAttributesRoundTrip) {
  Mat4 m;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m.m[size_t(r)][size_t(c)] = float(10 * r + c) + 0.25f;
  const ExrAttributes written = {{"software", std::string("Caligo test")}, {"caligo/samples", 37},
                                 {"caligo/renderTime", 1.5f}, {"worldToCamera", m}};
  write_exr(file("meta.exr"), test_image(3, 2, {"R", "G", "B"}), false, written);
  const ExrAttributes read = read_exr_attributes(file("meta.exr"));
  for (const ExrAttribute& a : written) {
    const ExrValue* v = find_attribute(read, a.name);
    ASSERT_NE(v, nullptr) << a.name;
    EXPECT_TRUE(*v == a.value) << a.name;
  }
  Imf::InputFile in(file("meta.exr").c_str());
  const auto* stored = in.header().findTypedAttribute<Imf::M44fAttribute>("worldToCamera");
  ASSERT_NE(stored, nullptr);
  EXPECT_EQ(stored->value()[0][1], m.m[1][0]);  // row vectors: M44f[i][j] = Mat4[j][i]
  // A structural name is OpenEXR's own: refused before the file is touched.
  EXPECT_THROW(write_exr(file("bad.exr"), test_image(1, 1, {"R"}), false, {{"dataWindow", 1}}), std::invalid_argument);
  EXPECT_FALSE(fs::exists(file("bad.exr")));
  EXPECT_THROW(read_exr_attributes(file("missing.exr")), InputError);
}

TEST_F(ExrIo, WritesZipCompressedFloatOrHalfChannels) {
  Image image = test_image(3, 2, {"R", "G", "B", "Z"});
  write_exr(file("float.exr"), image);
  write_exr(file("half.exr"), image, true);
  for (auto [name, type] : {std::pair{"float.exr", Imf::FLOAT}, std::pair{"half.exr", Imf::HALF}}) {
    Imf::InputFile in(file(name).c_str());
    EXPECT_EQ(in.header().compression(), Imf::ZIP_COMPRESSION);
    int count = 0;
    for (auto it = in.header().channels().begin(); it != in.header().channels().end(); ++it, ++count) {
      EXPECT_EQ(it.channel().type, type) << name << " " << it.name();
    }
    EXPECT_EQ(count, 4);
  }
}

TEST_F(ExrIo, HalfRoundTripIsWithinHalfPrecision) {
  Image image = test_image(6, 4, kAovChannels);
  write_exr(file("half.exr"), image, true);
  Image back = read_exr(file("half.exr"));
  ASSERT_EQ(back.channels(), image.channels());
  for (size_t i = 0; i < image.pixels().size(); ++i) {
    float v = image.pixels()[i];
    // Half has an 11-bit significand: round-to-nearest errs by at most 2^-11 relative, and by
    // half the smallest subnormal step (2^-25) near zero.
    float tolerance = std::max(std::abs(v) * std::exp2(-11.0f), std::exp2(-25.0f));
    EXPECT_NEAR(back.pixels()[i], v, tolerance) << "sample " << i;
  }
}

TEST_F(ExrIo, ChannelOrderPutsRgbaFirstInEachLayer) {
  // The order in which OpenEXR lists them: sorted byte-wise.
  std::vector<std::string> on_disk = {"A", "B", "G",        "N.X",      "N.Y",      "N.Z",
                                      "R", "Z", "albedo.B", "albedo.G", "albedo.R", "depth"};
  std::vector<std::string> expected = {"R",   "G",   "B",   "A",        "Z",        "depth",
                                       "N.X", "N.Y", "N.Z", "albedo.R", "albedo.G", "albedo.B"};
  EXPECT_EQ(exr_channel_order(on_disk), expected);
}

TEST_F(ExrIo, OverwritesAtomicallyAndLeavesNoTemporaryFiles) {
  write_exr(file("out.exr"), test_image(2, 2, {"R", "G", "B"}));
  Image second = test_image(3, 1, {"Y"});
  write_exr(file("out.exr"), second);
  expect_bit_identical(read_exr(file("out.exr")), second);
  EXPECT_EQ(files_in_dir(), 1u);
}

void expect_input_error_naming(const std::string& path) {
  try {
    read_exr(path);
    FAIL() << "expected InputError for " << path;
  } catch (const InputError& e) {
    std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find("cannot read OpenEXR file"), std::string::npos) << what;
    EXPECT_EQ(e.where().file, path);
  }
}

TEST_F(ExrIo, MissingFileIsAnInputErrorNamingIt) { expect_input_error_naming(file("missing.exr")); }

TEST_F(ExrIo, GarbageFileIsAnInputErrorNamingIt) {
  std::ofstream(file("garbage.exr")) << "this is not an OpenEXR file, just some text\n";
  expect_input_error_naming(file("garbage.exr"));
}

TEST_F(ExrIo, TruncatedFileIsAnInputErrorNamingIt) {
  write_exr(file("whole.exr"), test_image(64, 64, {"R", "G", "B"}));
  fs::resize_file(file("whole.exr"), fs::file_size(file("whole.exr")) / 2);
  expect_input_error_naming(file("whole.exr"));
}

TEST_F(ExrIo, WritingIntoAMissingDirectoryThrowsAndLeavesNothing) {
  std::string path = file("no_such_dir/out.exr");
  EXPECT_ANY_THROW(write_exr(path, test_image(2, 2, {"R", "G", "B"})));
  EXPECT_FALSE(fs::exists(dir_ / "no_such_dir"));
  EXPECT_EQ(files_in_dir(), 0u);
}

TEST_F(ExrIo, EmptyImageIsRejectedBeforeTouchingTheDisk) {
  EXPECT_THROW(write_exr(file("empty.exr"), Image(0, 3, {"R"})), std::invalid_argument);
  EXPECT_EQ(files_in_dir(), 0u);
}

}  // namespace
}  // namespace caligo
