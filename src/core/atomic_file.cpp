#include "core/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <system_error>

#include "core/error.h"

namespace caligo {

namespace fs = std::filesystem;

fs::path temp_path_beside(const fs::path& target, const char* tag) {
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

void flush_to_disk(const fs::path& file, const std::string& what_for) {
  const int fd = ::open(file.c_str(), O_RDONLY);
  if (fd < 0 || ::fsync(fd) != 0) {
    const std::string why = std::strerror(errno);
    if (fd >= 0) ::close(fd);
    throw EnvironmentError(what_for + ": cannot flush " + file.string() + " to the disk: " + why);
  }
  ::close(fd);
}

void remove_stale_temporaries(const fs::path& dir) {
  std::error_code ec;
  for (fs::directory_iterator it(dir.empty() ? fs::path(".") : dir, ec), end; !ec && it != end; it.increment(ec)) {
    // temp_path_beside's names: "." NAME ".tmp-" PID "-" N EXT.
    const std::string name = it->path().filename().string();
    const size_t tag = name.rfind(".tmp-");
    if (name.empty() || name[0] != '.' || tag == std::string::npos) continue;
    char* rest = nullptr;
    const long pid = std::strtol(name.c_str() + tag + 5, &rest, 10);
    if (pid <= 0 || rest == nullptr || *rest != '-') continue;
    // Alive (or someone else's: EPERM) is left alone.
    if (::kill(pid_t(pid), 0) != 0 && errno == ESRCH) {
      std::error_code ignored;
      fs::remove(it->path(), ignored);
    }
  }
}

void write_file_atomically(const std::string& path, const std::function<void(const std::string& temp_path)>& write) {
  const fs::path temp = temp_path_beside(fs::path(path), ".tmp-");
  const auto discard = [&] {
    std::error_code ignored;  // best effort: the original error is the one worth reporting
    fs::remove(temp, ignored);
  };
  try {
    write(temp.string());
    flush_to_disk(temp, path);
    fs::rename(temp, path);
  } catch (const InputError&) {
    discard();
    throw;
  } catch (const std::invalid_argument&) {
    discard();
    throw;
  } catch (const std::exception& e) {
    discard();
    throw EnvironmentError(path + ": cannot write (nothing was replaced): " + write_failure_reason(e));
  }
}

std::string write_failure_reason(const std::exception& e) {
  const std::string what = e.what();
  const std::string tag = "(nothing was replaced): ";
  const size_t at = what.rfind(tag);
  return at == std::string::npos ? what : what.substr(at + tag.size());
}

}  // namespace caligo
