// The fixture of the end-to-end tests: runs the real caligo binary in a fresh folder per test
// and captures its exit code, stdout and stderr.
#pragma once

#include <gtest/gtest.h>

#include <sys/mount.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace caligo_cli {

namespace fs = std::filesystem;

struct RunResult {
  int exit_code;
  std::string out, err;
};

inline std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

class CliFixture : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("caligo-cli-" + std::to_string(::getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    for (const fs::path& m : mounts_) ::umount2(m.c_str(), MNT_DETACH);
    fs::remove_all(dir_);
  }

  // A small tmpfs at dir_/name ("size=64k", ...), unmounted at the end; false where mounting is
  // not allowed (not root, a container without CAP_SYS_ADMIN).
  bool mount_tmpfs(const std::string& name, const std::string& options) {
    const fs::path at = dir_ / name;
    fs::create_directories(at);
    if (::mount("tmpfs", at.c_str(), "tmpfs", 0, options.c_str()) != 0) return false;
    mounts_.push_back(at);
    return true;
  }
  void remount_read_only(const std::string& name) {
    ::mount("tmpfs", (dir_ / name).c_str(), "tmpfs", MS_REMOUNT | MS_RDONLY, "size=1m");
  }

  RunResult run(const std::string& args) const { return run_with_env("", args); }

  // `env` is prepended to the command line ("NAME=value ...").
  RunResult run_with_env(const std::string& env, const std::string& args) const {
    const fs::path out = dir_ / "stdout.txt", err = dir_ / "stderr.txt";
    const std::string command =
        env + " " + std::string(CALIGO_BINARY) + " " + args + " >" + out.string() + " 2>" + err.string();
    const int status = std::system(command.c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
  }

  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }

  // Every .exr or .png file in the directory.
  std::vector<std::string> outputs() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_)) {
      const std::string n = e.path().filename().string();
      if (n.find(".exr") != std::string::npos || n.find(".png") != std::string::npos) names.push_back(n);
    }
    return names;
  }

  fs::path dir_;
  std::vector<fs::path> mounts_;
};

}  // namespace caligo_cli
