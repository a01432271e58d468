// write_file_atomically: the target appears complete or not at all, and no temporary is left.
#include "core/atomic_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/error.h"

namespace caligo {
namespace {

namespace fs = std::filesystem;

// A fresh, empty directory per test, removed afterwards.
class AtomicFileTest : public testing::Test {
 protected:
  void SetUp() override {
    const auto* info = testing::UnitTest::GetInstance()->current_test_info();
    // The pid keeps concurrent runs of this binary (several build trees) apart.
    dir_ = fs::temp_directory_path() /
           ("caligo_atomic_file_test_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_)) names.push_back(e.path().filename().string());
    return names;
  }

  fs::path dir_;
};

void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + path);
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST_F(AtomicFileTest, WritesContentAndLeavesNoTemporary) {
  const fs::path target = dir_ / "out.exr";
  std::string temp_seen;
  write_file_atomically(target.string(), [&](const std::string& temp) {
    temp_seen = temp;
    write_text(temp, "pixels");
  });
  EXPECT_EQ(read_text(target), "pixels");
  EXPECT_EQ(entries(), std::vector<std::string>{"out.exr"});
  // The temporary lived beside the target and kept its extension, for extension-driven codecs.
  EXPECT_EQ(fs::path(temp_seen).parent_path(), dir_);
  EXPECT_EQ(fs::path(temp_seen).extension(), ".exr");
  EXPECT_NE(fs::path(temp_seen).filename(), "out.exr");
}

TEST_F(AtomicFileTest, ReplacesExistingFile) {
  const fs::path target = dir_ / "image.png";
  write_text(target.string(), "old");
  write_file_atomically(target.string(), [](const std::string& temp) { write_text(temp, "new"); });
  EXPECT_EQ(read_text(target), "new");
  EXPECT_EQ(entries(), std::vector<std::string>{"image.png"});
}

TEST_F(AtomicFileTest, ThrowingWriterCreatesNothing) {
  const fs::path target = dir_ / "out.exr";
  const auto failing = [](const std::string& temp) {
    write_text(temp, "half a fi");
    throw std::runtime_error("disk full");
  };
  EXPECT_THROW(write_file_atomically(target.string(), failing), std::runtime_error);
  EXPECT_FALSE(fs::exists(target));
  EXPECT_TRUE(entries().empty());
}

TEST_F(AtomicFileTest, ThrowingWriterLeavesExistingFileUnchanged) {
  const fs::path target = dir_ / "out.exr";
  write_text(target.string(), "previous render");
  const auto failing = [](const std::string& temp) {
    write_text(temp, "partial");
    throw std::runtime_error("interrupted");
  };
  EXPECT_THROW(write_file_atomically(target.string(), failing), std::runtime_error);
  EXPECT_EQ(read_text(target), "previous render");
  EXPECT_EQ(entries(), std::vector<std::string>{"out.exr"});
}

TEST_F(AtomicFileTest, WriterThatCreatesNothingFailsCleanly) {
  const fs::path target = dir_ / "out.txt";
  EXPECT_THROW(write_file_atomically(target.string(), [](const std::string&) {}), EnvironmentError);
  EXPECT_TRUE(entries().empty());
}

TEST_F(AtomicFileTest, TemporaryNamesAreUnique) {
  const fs::path target = dir_ / "a.txt";
  std::string first, second;
  write_file_atomically(target.string(), [&](const std::string& t) {
    first = t;
    write_text(t, "1");
  });
  write_file_atomically(target.string(), [&](const std::string& t) {
    second = t;
    write_text(t, "2");
  });
  EXPECT_NE(first, second);
  EXPECT_EQ(read_text(target), "2");
}

// Only what a dead caligo left: our exact name shape, a dead PID, an hour untouched. A user's
// file that merely looks similar, a fresh temporary (a writer on another host may own it) and
// a live process's are kept.
TEST_F(AtomicFileTest, OnlyStaleTemporariesOfOursAreRemoved) {
  const auto make = [&](const std::string& name, bool old) {
    write_text((dir_ / name).string(), "x");
    if (old) fs::last_write_time(dir_ / name, fs::file_time_type::clock::now() - std::chrono::hours(2));
  };
  const std::string dead = "4194303";  // pid_max's top: no process of a test machine has it
  const std::string alive = std::to_string(::getpid());
  make(".out.exr.tmp-" + dead + "-3.exr", true);   // stale: removed
  make(".out.exr.tmp-" + dead + "-4.exr", false);  // fresh: kept
  make(".out.exr.tmp-" + alive + "-5.exr", true);  // alive: kept
  make(".backup.tmp-2023-05.tar", true);           // not ours: kept
  make(".out.exr.tmp-" + dead + "-6.png", true);   // extension differs: kept
  remove_stale_temporaries(dir_);
  std::vector<std::string> left = entries();
  std::sort(left.begin(), left.end());
  std::vector<std::string> kept = {".backup.tmp-2023-05.tar", ".out.exr.tmp-" + dead + "-4.exr",
                                   ".out.exr.tmp-" + dead + "-6.png", ".out.exr.tmp-" + alive + "-5.exr"};
  std::sort(kept.begin(), kept.end());
  EXPECT_EQ(left, kept);
}

}  // namespace caligo
