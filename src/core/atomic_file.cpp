#include "core/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <system_error>

namespace caligo {
std::filesystem::path temp_path_beside(const std::filesystem::path& target, const char* tag) {
  static std::atomic<uint64_t> counter{0};
  // Appended piecewise: GCC 12 warns falsely (-Wrestrict) about `"." + std::string`.
  std::string name = ".";
  name += target.filename().string();
  name += tag;
  name += std::to_string(::getpid());
  name += '-';
  name += std::to_string(counter.fetch_add(1));
  name += target.extension().string();
  return target.parent_path() / name;
}

void write_file_atomically(const std::string& path,
                           const std::function<void(const std::string& temp_path)>& write) {
  const std::filesystem::path temp = temp_path_beside(std::filesystem::path(path), ".tmp-");
  try {
    write(temp.string());
    std::filesystem::rename(temp, path);
  } catch (...) {
    std::error_code ignored;  // best effort: the original error is the one worth reporting
    std::filesystem::remove(temp, ignored);
    throw;
  }
}

}  // namespace caligo
