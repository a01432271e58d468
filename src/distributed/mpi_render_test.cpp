// End-to-end: `mpirun -np N caligo render` through the real binary and Open MPI's launcher on
// loopback. The merged frame must equal the single-process render bit for bit (every channel
// of the EXR, compared exactly); a failing rank must be reported once, on rank 0, with a
// non-zero exit and nothing written; a killed rank must end the job, not hang it.
// Registered only where MPI and mpirun were found (CMakeLists.txt).
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "image/exr_io.h"

namespace {

namespace fs = std::filesystem;

struct RunResult {
  int exit_code;
  std::string err;
};

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// As CI runs it: as root, more ranks than cores allowed, loopback only. A wall-clock limit
// turns a hang into exit code 124.
std::string mpirun(int ranks) {
  return "timeout 60 " + std::string(MPIEXEC) + " --allow-run-as-root --oversubscribe -np " + std::to_string(ranks) +
         " ";
}

// The small scene every test renders: fog, a glass sphere, light through both (a few ms a pass).
const std::string kScene = "render default --res 40x30 --spp 5 --threads 1 -q";
const std::string kGuidedScene = "render default --res 40x30 --spp 12 --threads 1 -q --guiding all";

class MpiRender : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("caligo-mpi-" + std::to_string(::getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // `prefix`: environment assignments and the launcher, before the binary.
  RunResult run(const std::string& prefix, const std::string& args) const {
    return run_command(prefix + " " + std::string(CALIGO_BINARY) + " " + args);
  }
  RunResult run_command(const std::string& command) const {
    const fs::path err = dir_ / "stderr.txt";
    const int status = std::system((command + " >/dev/null 2>" + err.string()).c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(err)};
  }

  // Renders `args` with one process and with `ranks` under mpirun; both images must match exactly.
  void expect_same_as_single_process(int ranks, const std::string& args) const {
    const fs::path a = dir_ / "single.exr", b = dir_ / "mpi.exr";
    const RunResult single = run("", args + " -o " + a.string());
    ASSERT_EQ(single.exit_code, 0) << single.err;
    const RunResult mpi = run(mpirun(ranks), args + " -o " + b.string());
    ASSERT_EQ(mpi.exit_code, 0) << mpi.err;
    const caligo::Image x = caligo::read_exr(a.string()), y = caligo::read_exr(b.string());
    ASSERT_EQ(x.channels(), y.channels());
    ASSERT_EQ(x.width(), y.width());
    ASSERT_EQ(x.height(), y.height());
    const auto p = x.pixels(), q = y.pixels();
    ASSERT_EQ(p.size(), q.size());
    size_t differ = 0;
    for (size_t i = 0; i < p.size(); ++i) differ += std::memcmp(&p[i], &q[i], sizeof(float)) != 0;
    EXPECT_EQ(differ, 0u) << "of " << p.size() << " values";
    EXPECT_TRUE(fs::exists(dir_ / "mpi.png"));
  }

  // The .exr and .png files in the test's folder.
  int outputs() const {
    int n = 0;
    for (const auto& e : fs::directory_iterator(dir_))
      n += e.path().extension() == ".exr" || e.path().extension() == ".png";
    return n;
  }

  fs::path dir_;
};

// Two ranks split the 5 samples as 3 + 2 (the film sums are exact integers, so the merge is too).
TEST_F(MpiRender, SampleSplitEqualsSingleProcessBitForBit) {
  expect_same_as_single_process(2, kScene + " --aov all");
}

// Three ranks (oversubscribed) render bands of rows of a crop window, each band all 5 samples.
TEST_F(MpiRender, RowSplitEqualsSingleProcessBitForBit) {
  expect_same_as_single_process(3, kScene + " --crop 0.1,0.9,0.2,0.95 --mpi-split rows");
}

// Rank 1 fails with a scene error: rank 0 says which rank and why, once; exit 2; nothing written.
// Path guiding over ranks: each training iteration split over them, the field's statistics
// summed exactly after it (--spp 12 trains through iteration 3 and renders 5 samples after).
TEST_F(MpiRender, GuidedSampleSplitEqualsSingleProcessBitForBit) {
  expect_same_as_single_process(2, kGuidedScene);
}

TEST_F(MpiRender, GuidedRowSplitEqualsSingleProcessBitForBit) {
  expect_same_as_single_process(2, kGuidedScene + " --mpi-split rows");
}

TEST_F(MpiRender, FailingRankIsReportedOnRankZero) {
  const RunResult r = run("CALIGO_TEST_MPI_FAIL=1:input " + mpirun(2), kScene + " -o " + (dir_ / "a.exr").string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("caligo: error: rank 1 of 2 failed: CALIGO_TEST_MPI_FAIL: a scene error injected on rank 1"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("caligo: error"), r.err.rfind("caligo: error")) << "reported more than once:\n" << r.err;
  EXPECT_EQ(outputs(), 0);
  // An internal failure on rank 0 itself keeps its kind (exit 1).
  const RunResult r0 = run("CALIGO_TEST_MPI_FAIL=0:throw " + mpirun(2), kScene + " -o " + (dir_ / "a.exr").string());
  EXPECT_EQ(r0.exit_code, 1) << r0.err;
  EXPECT_NE(r0.err.find("rank 0 of 2 failed: internal: a failure injected on rank 0"), std::string::npos) << r0.err;
  EXPECT_EQ(outputs(), 0);
}

// Ranks started with other options (MPMD syntax: one command line per rank) stop before
// rendering: exit 2, one message, nothing written.
TEST_F(MpiRender, RanksThatDisagreeOnTheFrameStop) {
  const std::string out = " -o " + (dir_ / "a.exr").string();
  const std::string second = " : -np 1 " + std::string(CALIGO_BINARY) + " " + kScene + " --seed 9" + out;
  const RunResult r = run("timeout 60 " + std::string(MPIEXEC) + " --allow-run-as-root --oversubscribe -np 1",
                          kScene + out + second);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("caligo: error: the 2 ranks of the MPI job disagree on the frame"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("caligo: error"), r.err.rfind("caligo: error")) << r.err;
  EXPECT_EQ(outputs(), 0);
}

// Ranks whose frame keys differ (caligo's hash of the scene file and of the options the
// settings' fingerprint does not cover) stop the same way; equal keys render. Driven through
// render_frame directly (mpi_frame_key_probe.cpp), one key per rank.
TEST_F(MpiRender, RanksWithDifferentFrameKeysStop) {
  const std::string launcher = "timeout 60 " + std::string(MPIEXEC) + " --allow-run-as-root --oversubscribe -np 1";
  const std::string probe = std::string(FRAME_KEY_PROBE);
  const RunResult same = run_command(launcher + " " + probe + " 12345678901234567 : -np 1 " + probe + " 12345678901234567");
  EXPECT_EQ(same.exit_code, 0) << same.err;
  const RunResult r = run_command(launcher + " " + probe + " 12345678901234567 : -np 1 " + probe + " 12345678901234568");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("caligo: error: the 2 ranks of the MPI job disagree on the frame"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("caligo: error"), r.err.rfind("caligo: error")) << r.err;
}

// A rank killed by a signal cannot report: mpirun notices and ends the job (not a hang, which
// `timeout` would report as 124), non-zero, nothing written.
TEST_F(MpiRender, KilledRankEndsTheJob) {
  const RunResult r = run("CALIGO_TEST_MPI_FAIL=1:kill " + mpirun(2), kScene + " -o " + (dir_ / "a.exr").string());
  EXPECT_NE(r.exit_code, 0) << r.err;
  EXPECT_NE(r.exit_code, 124) << "the job hung:\n" << r.err;
  EXPECT_NE(r.err.find("rank 1"), std::string::npos) << r.err;
  EXPECT_EQ(outputs(), 0);
}

}  // namespace
