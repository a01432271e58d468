// caligo render --denoise and caligo denoise through the binary: the beauty is the plain
// render's bit for bit, the layers are written, the denoise command reproduces the denoised
// layer, and bad inputs are refused with exit 2 and no output.
#include <algorithm>
#include <cstring>

#include "cli_testing.h"
#include "image/exr_io.h"

namespace {

using namespace caligo_cli;

class Denoise : public CliFixture {};

TEST_F(Denoise, RenderDenoiseKeepsTheBeautyAndAddsTheLayers) {
  const std::string common = "render default --res 40x30 --spp 8 --seed 5 -q ";
  ASSERT_EQ(run(common + "-o " + (dir_ / "plain.exr").string()).exit_code, 0);
  const RunResult r = run(common + "--denoise -o " + (dir_ / "d.exr").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const caligo::Image plain = caligo::read_exr((dir_ / "plain.exr").string());
  const caligo::Image d = caligo::read_exr((dir_ / "d.exr").string());
  for (const char* layer : {"half_a.", "half_b.", "denoised.", "variance.", "albedo.", "N."})
    EXPECT_TRUE(d.has_channel(std::string(layer) + (std::strcmp(layer, "N.") ? "R" : "X"))) << layer;
  // Two halves merged are the one render: the beauty is the same bits.
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x)
      for (int c = 0; c < 3; ++c) ASSERT_EQ(d.at(x, y, c), plain.at(x, y, c)) << x << "," << y;
  EXPECT_TRUE(fs::exists(dir_ / "d.png"));
  // The command on that file makes the same denoised layer.
  const RunResult again = run("denoise " + (dir_ / "d.exr").string() + " -o " + (dir_ / "again.exr").string());
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.err.find("estimated MSE"), std::string::npos) << again.err;
  const caligo::Image a = caligo::read_exr((dir_ / "again.exr").string());
  const auto dc = *d.rgb_indices("denoised."), ac = *a.rgb_indices("denoised.");
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x)
      for (int c = 0; c < 3; ++c) ASSERT_EQ(a.at(x, y, ac[size_t(c)]), d.at(x, y, dc[size_t(c)]));
}

TEST_F(Denoise, BadInputsAreRefusedWithNothingWritten) {
  ASSERT_EQ(run("render default --res 16x12 --spp 4 -q -o " + (dir_ / "plain.exr").string()).exit_code, 0);
  const RunResult missing = run("denoise " + (dir_ / "plain.exr").string() + " -o " + (dir_ / "out.exr").string());
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("half_a"), std::string::npos) << missing.err;
  EXPECT_NE(missing.err.find("plain.exr"), std::string::npos) << missing.err;
  EXPECT_FALSE(fs::exists(dir_ / "out.exr"));
  EXPECT_FALSE(fs::exists(dir_ / "out.png"));
  write("garbage.exr", "not an exr");
  EXPECT_EQ(run("denoise " + (dir_ / "garbage.exr").string() + " -o " + (dir_ / "out.exr").string()).exit_code, 2);
  EXPECT_EQ(run("denoise " + (dir_ / "plain.exr").string() + " -o " + (dir_ / "plain.exr").string()).exit_code, 2);
  EXPECT_EQ(run("denoise " + (dir_ / "plain.exr").string() + " -o " + (dir_ / "out.png").string()).exit_code, 2);
  EXPECT_EQ(run("denoise " + (dir_ / "plain.exr").string() + " --radius 0 -o " + (dir_ / "out.exr").string()).exit_code, 2);
  // A reference of another size is refused, naming it, and nothing is written.
  ASSERT_EQ(run("render default --res 16x12 --spp 4 --denoise -q -o " + (dir_ / "d.exr").string()).exit_code, 0);
  ASSERT_EQ(run("render default --res 8x6 --spp 4 -q -o " + (dir_ / "small.exr").string()).exit_code, 0);
  const RunResult mismatch = run("denoise " + (dir_ / "d.exr").string() + " --reference " + (dir_ / "small.exr").string() +
                                 " -o " + (dir_ / "dd.exr").string());
  EXPECT_EQ(mismatch.exit_code, 2);
  EXPECT_NE(mismatch.err.find("small.exr"), std::string::npos) << mismatch.err;
  EXPECT_NE(mismatch.err.find("8x6"), std::string::npos) << mismatch.err;
  EXPECT_FALSE(fs::exists(dir_ / "dd.exr"));
  EXPECT_FALSE(fs::exists(dir_ / "dd.strip.png"));
  const RunResult few = run("render default --res 16x12 --spp 2 --denoise -o " + (dir_ / "few.exr").string());
  EXPECT_EQ(few.exit_code, 2);
  EXPECT_NE(few.err.find("at least 4 samples"), std::string::npos) << few.err;
  const RunResult timed = run("render default --res 16x12 --spp 8 --denoise --time-limit 5s -o " + (dir_ / "t.exr").string());
  EXPECT_EQ(timed.exit_code, 2);
  EXPECT_FALSE(fs::exists(dir_ / "few.exr"));
  EXPECT_FALSE(fs::exists(dir_ / "t.exr"));
}

}  // namespace

namespace {

// Interrupted by SIGINT after its first passes, --denoise writes the denoised partial image
// (every pixel with samples: the halves refine the whole frame) and no checkpoint; exit 130.
TEST_F(Denoise, AnInterruptedDenoisedRenderWritesTheDenoisedPartialImage) {
  const RunResult r = run_with_env("timeout --preserve-status -s INT 2.5",
                                   "render lamp-in-fog --res 64x48 --spp 100000 --denoise --aov default,samples -q -o " +
                                       (dir_ / "i.exr").string());
  if (r.err.find("interrupted") == std::string::npos) GTEST_SKIP() << "the signal came before the handler (a loaded machine)";
  ASSERT_EQ(r.exit_code, 130) << r.err;
  EXPECT_NE(r.err.find("no checkpoint"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "i.exr"));
  EXPECT_FALSE(fs::exists(dir_ / "i.ckpt"));
  const caligo::Image partial = caligo::read_exr((dir_ / "i.partial.exr").string());
  const auto d = *partial.rgb_indices("denoised.");
  const int samples = partial.channel_index("samples");
  ASSERT_GE(samples, 0);
  double sum = 0;
  float fewest = 1e30f;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) {
      sum += partial.at(x, y, d[1]);
      fewest = std::min(fewest, partial.at(x, y, samples));
    }
  EXPECT_GT(sum, 0.0);
  EXPECT_GE(fewest, 2.0f) << "every pixel has both halves' first pass: a whole picture, not finished tiles";
}

}  // namespace
