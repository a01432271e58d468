// What the fuzz targets share: the contract they check and a file for readers that take a path.
//
// The contract: whatever the bytes, a reader returns a value or throws InputError. Any other
// exception escapes the target and aborts (libFuzzer reports it as a crash with the input),
// as do ASan and UBSan findings (-fno-sanitize-recover) and libFuzzer's own limits (time per
// input, RSS, single allocations).
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"

namespace caligo::fuzz {

// A folder private to this process (in /dev/shm where it exists: no disk traffic per input),
// removed at exit. Relative paths in fuzzed files resolve here, so they find nothing.
inline const std::string& scratch_dir() {
  struct Dir {
    std::string path;
    Dir() {
      const std::filesystem::path shm = "/dev/shm";
      const std::filesystem::path base = std::filesystem::is_directory(shm) ? shm : std::filesystem::temp_directory_path();
      path = (base / ("caligo-fuzz-" + std::to_string(getpid()))).string();
      std::filesystem::create_directories(path);
    }
    ~Dir() {
      std::error_code ec;
      std::filesystem::remove_all(path, ec);
    }
  };
  static const Dir dir;
  return dir.path;
}

// Writes the input to scratch_dir()/input<extension> and returns that path.
inline std::string input_file(const uint8_t* data, size_t size, const std::string& extension) {
  const std::string path = scratch_dir() + "/input" + extension;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  if (!out.flush()) {
    std::perror(path.c_str());
    std::abort();
  }
  return path;
}

// Runs `read`; an InputError is a correct answer to hostile input, anything else escapes.
template <typename Read>
void expect_value_or_input_error(Read&& read) {
  try {
    read();
  } catch (const InputError&) {
  }
}

}  // namespace caligo::fuzz
