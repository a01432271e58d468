#include "core/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cctype>
#include <chrono>
#include <cstdlib>
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

namespace {

// Whether `name` is exactly what temp_path_beside makes: "." BASE TAG PID "-" N EXT, with
// EXT the extension of BASE; returns the PID, or 0.
long temporary_pid(const std::string& name) {
  const size_t tag = name.rfind(".tmp-");
  if (name.size() < 2 || name[0] != '.' || tag == std::string::npos || tag < 2) return 0;
  const std::string base = name.substr(1, tag - 1), ext = fs::path(base).extension().string();
  size_t i = tag + 5, pid_end = i;
  while (pid_end < name.size() && std::isdigit(static_cast<unsigned char>(name[pid_end]))) ++pid_end;
  if (pid_end == i || pid_end - i > 7 || pid_end >= name.size() || name[pid_end] != '-') return 0;
  size_t n_end = pid_end + 1;
  while (n_end < name.size() && std::isdigit(static_cast<unsigned char>(name[n_end]))) ++n_end;
  if (n_end == pid_end + 1 || name.compare(n_end, std::string::npos, ext) != 0) return 0;
  return std::strtol(name.c_str() + i, nullptr, 10);
}

}  // namespace

void remove_stale_temporaries(const fs::path& dir) {
  // Only an hour after their last write: a PID says nothing about a writer on another host
  // sharing the folder (NFS) or in another PID namespace, and no write of ours pauses that long.
  const auto old = fs::file_time_type::clock::now() - std::chrono::hours(1);
  std::error_code ec;
  for (fs::directory_iterator it(dir.empty() ? fs::path(".") : dir, ec), end; !ec && it != end; it.increment(ec)) {
    const long pid = temporary_pid(it->path().filename().string());
    std::error_code e;
    if (pid <= 0 || !it->is_regular_file(e) || it->last_write_time(e) > old || e) continue;
    // Alive (or someone else's: EPERM) is left alone.
    if (::kill(pid_t(pid), 0) != 0 && errno == ESRCH) fs::remove(it->path(), e);
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
