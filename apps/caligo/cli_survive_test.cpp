// Renders that survive, through the real binary: SIGTERM at random points and --resume to the
// identical image; checkpoints that continue to more samples; checkpoints of another render
// refused; progressive stops; outputs checked before the render (bad -o in milliseconds,
// read-only folders exit 3) and written as one transaction (a full disk replaces nothing);
// numeric options validated.
#include <chrono>
#include <random>

#include "cli_testing.h"
#include "image/exr_io.h"
#include "render/film.h"

namespace {

using namespace caligo_cli;

class Survive : public CliFixture {};

std::vector<float> pixels(const fs::path& exr) {
  const caligo::Image image = caligo::read_exr(exr.string());
  return {image.pixels().begin(), image.pixels().end()};
}

constexpr const char* kScene = "lamp-in-fog --res 48x32 -q";

TEST_F(Survive, TerminatedRendersResumeToTheIdenticalImage) {
  const fs::path full = dir_ / "full.exr";
  ASSERT_EQ(run(std::string("render ") + kScene + " --spp 1024 -o " + full.string()).exit_code, 0);
  const auto started = std::chrono::steady_clock::now();
  ASSERT_EQ(run(std::string("render ") + kScene + " --spp 1024 -o " + (dir_ / "timing.exr").string()).exit_code, 0);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  // Three renders, each terminated once or twice at random times and resumed to the end.
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> when(0.05, std::max(0.1, 0.8 * seconds));
  int interrupted = 0;
  for (int trial = 0; trial < 3; ++trial) {
    const fs::path part = dir_ / ("part" + std::to_string(trial) + ".exr");
    const fs::path checkpoint = dir_ / ("part" + std::to_string(trial) + ".ckpt");
    const fs::path partial = dir_ / ("part" + std::to_string(trial) + ".partial.exr");
    std::string resume;
    for (int cut = 0; cut <= trial % 2; ++cut) {
      char delay[32];
      std::snprintf(delay, sizeof delay, "%.3f", when(rng));
      const RunResult r = run_with_env(std::string("timeout --preserve-status -s TERM ") + delay,
                                       std::string("render ") + kScene + " --spp 1024 -o " + part.string() + resume);
      if (r.exit_code == 0) break;  // finished before the signal came
      ASSERT_EQ(r.exit_code, 128 + 15) << r.err;
      // A signal that comes before main installs its handler (a loaded machine) kills the
      // process outright: nothing is saved and the trial starts over.
      if (r.err.find("interrupted") == std::string::npos && !fs::exists(checkpoint)) {
        resume.clear();
        continue;
      }
      EXPECT_NE(r.err.find("--resume"), std::string::npos) << r.err;
      ASSERT_TRUE(fs::exists(checkpoint) && fs::exists(partial));
      resume = " --resume " + checkpoint.string();
      ++interrupted;
    }
    const RunResult r = run(std::string("render ") + kScene + " --spp 1024 -o " + part.string() + resume);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(pixels(part), pixels(full)) << "trial " << trial;
  }
  EXPECT_GT(interrupted, 0) << "no render was interrupted: the test proved nothing";
}

TEST_F(Survive, CheckpointsContinueToMoreSamples) {
  const fs::path a = dir_ / "a.exr", b = dir_ / "b.exr", ckpt = dir_ / "a.ckpt";
  ASSERT_EQ(run(std::string("render ") + kScene + " --spp 24 -o " + b.string()).exit_code, 0);
  const RunResult first =
      run(std::string("render ") + kScene + " --spp 8 --checkpoint " + ckpt.string() + " --checkpoint-every 0.001 -o " +
          a.string());
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const caligo::Film saved = caligo::Film::load(ckpt.string());
  EXPECT_EQ(saved.sample_count(0, 0), 8u);
  EXPECT_EQ(saved.sample_count(47, 31), 8u);
  const RunResult more = run(std::string("render ") + kScene + " --spp 24 --resume " + ckpt.string() + " -o " + a.string());
  ASSERT_EQ(more.exit_code, 0) << more.err;
  EXPECT_EQ(pixels(a), pixels(b));
}

TEST_F(Survive, CheckpointsOfAnotherRenderAreRefused) {
  const fs::path ckpt = dir_ / "c.ckpt", out = dir_ / "c.exr";
  ASSERT_EQ(run(std::string("render ") + kScene + " --spp 2 --checkpoint " + ckpt.string() + " -o " + out.string())
                .exit_code,
            0);
  for (const std::string& other : {std::string("furnace --res 48x32 -q"), std::string(kScene) + " --seed 7",
                                   std::string(kScene) + " --max-bounces 2", std::string(kScene) + " --aov all"}) {
    const RunResult r = run("render " + other + " --spp 4 --resume " + ckpt.string() + " -o " + (dir_ / "d.exr").string());
    EXPECT_EQ(r.exit_code, 2) << other << ": " << r.err;
    EXPECT_NE(r.err.find(ckpt.string()), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "d.exr"));
  }
  const fs::path junk = write("junk.ckpt", "not a film");
  const RunResult r = run(std::string("render ") + kScene + " --spp 4 --resume " + junk.string() + " -o " + out.string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("junk.ckpt"), std::string::npos) << r.err;
}

TEST_F(Survive, TimeLimitStopsWithEveryPixelAtTheSameCount) {
  const fs::path out = dir_ / "t.exr", ckpt = dir_ / "t.ckpt";
  const auto started = std::chrono::steady_clock::now();
  const RunResult r = run("render lamp-in-fog --res 48x32 --spp 1000000 --time-limit 0.5s --checkpoint " +
                          ckpt.string() + " -o " + out.string());
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("stopped by the time limit"), std::string::npos) << r.err;
  EXPECT_LT(seconds, 5.0);  // the budget plus start-up, with room for a loaded machine
  const caligo::Film film = caligo::Film::load(ckpt.string());
  const uint32_t n = film.sample_count(0, 0);
  EXPECT_LT(n, 1000000u);
  // On a loaded machine a pass can outlast the limit; the limit then cuts it (and says so).
  if (r.err.find("cut the last pass") != std::string::npos) return;
  EXPECT_GT(n, 0u);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 48; ++x) ASSERT_EQ(film.sample_count(x, y), n);
}

TEST_F(Survive, TargetRmseStopsAtTheEstimatedError) {
  const fs::path out = dir_ / "r.exr";
  const RunResult r = run("render furnace --res 16x16 --spp 1000000 --target-rmse 0.02 -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("stopped by the target RMSE"), std::string::npos) << r.err;
  // The furnace's every pixel is 2 exactly: the real RMSE, from the image, is near the estimate.
  const caligo::Image image = caligo::read_exr(out.string());
  double sum2 = 0.0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x)
      for (int c = 0; c < 3; ++c) sum2 += std::pow(image.at(x, y, c) - 2.0, 2.0);
  const double rmse = std::sqrt(sum2 / (16 * 16 * 3));
  EXPECT_LT(rmse, 0.02 * 1.5);
  EXPECT_TRUE(image.has_channel("variance.G"));
}

TEST_F(Survive, BadOutputsFailBeforeTheRender) {
  fs::create_directories(dir_ / "folder.exr");
  const std::string slow = "render default --spp 100000 -q -o ";
  const auto check = [&](const std::string& output, int code, const std::string& says) {
    const auto started = std::chrono::steady_clock::now();
    const RunResult r = run(slow + output);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    EXPECT_EQ(r.exit_code, code) << output << ": " << r.err;
    EXPECT_NE(r.err.find(says), std::string::npos) << output << ": " << r.err;
    EXPECT_LT(seconds, 10.0) << output;  // the render itself would take hours
  };
  check((dir_ / "folder.exr").string(), 2, "is a folder");
  check((dir_ / "missing" / "x.exr").string(), 2, "does not exist");
  check("''", 2, "empty");
  check((dir_ / "x.png").string(), 2, ".exr");
  if (!mount_tmpfs("ro", "size=1m")) GTEST_SKIP() << "cannot mount a tmpfs here (needs root)";
  remount_read_only("ro");
  check((dir_ / "ro" / "x.exr").string(), 3, "cannot create");
}

TEST_F(Survive, AFullDiskReplacesNothing) {
  if (!mount_tmpfs("small", "size=16k")) GTEST_SKIP() << "cannot mount a tmpfs here (needs root)";
  const fs::path small = dir_ / "small";
  std::ofstream(small / "out.exr") << "old exr";
  std::ofstream(small / "out.png") << "old png";
  const RunResult r = run("render default --res 96x72 --spp 1 -q --aov all -o " + (small / "out.exr").string());
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("nothing was replaced"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(small / "out.exr"), "old exr");
  EXPECT_EQ(slurp(small / "out.png"), "old png");
  int files = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(small)) ++files;
  EXPECT_EQ(files, 2) << "temporary files were left behind";
}

TEST_F(Survive, NumericOptionsAreValidated) {
  const std::string out = " -q -o " + (dir_ / "n.exr").string();
  for (const std::string& bad : std::vector<std::string>{"--seed -1", "--exposure nan", "--exposure 1e30", "--checkpoint-every 0 --checkpoint x.ckpt",
                                "--time-limit abc", "--time-limit -5", "--target-rmse -1", "--target-rmse nan",
                                "--spp 0", "--threads 0", "--crop 0,1,0,nan"}) {
    const RunResult r = run("render furnace --res 8x8 " + bad + out);
    EXPECT_EQ(r.exit_code, 2) << bad << ": " << r.err;
  }
  ASSERT_EQ(run("render furnace --res 8x8 --spp 1" + out).exit_code, 0);
  const RunResult nan = run("compare " + (dir_ / "n.exr").string() + " " + (dir_ / "n.exr").string() + " --max-rmse nan");
  EXPECT_EQ(nan.exit_code, 2) << nan.err;
  EXPECT_TRUE(fs::exists(dir_ / "n.exr"));
}

}  // namespace

namespace {

using namespace caligo_cli;

class Limits : public CliFixture {};

// A film larger than the machine's free memory is refused before the render, with the estimate.
TEST_F(Limits, AFilmTooLargeForMemoryIsRefusedFirst) {
  const uint64_t need = caligo::Film::memory_estimate({16384, 4096}, caligo::AovSet::all());
  std::ifstream meminfo("/proc/meminfo");
  std::string key, unit;
  uint64_t kib = 0, available = 0;
  while (meminfo >> key >> kib >> unit)
    if (key == "MemAvailable:") available = kib * 1024;
  if (available == 0 || available >= need) GTEST_SKIP() << "this machine has room for the film";
  const RunResult r = run("render furnace --res 16384x4096 --aov all --spp 1 -q -o " + (dir_ / "big.exr").string());
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find(std::to_string(need >> 20) + " MiB"), std::string::npos) << r.err;
  EXPECT_TRUE(outputs().empty());
}

}  // namespace
