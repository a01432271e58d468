#include "core/output_transaction.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "core/atomic_file.h"
#include "core/error.h"

namespace caligo {
namespace {

namespace fs = std::filesystem;


}  // namespace

void check_output_path(const std::string& path, const std::string& what) {
  const SourceLocation where{path, ""};
  if (path.empty()) throw InputError("the " + what + " output path is empty");
  const fs::path p(path);
  if (p.filename().empty() || p.filename() == "." || p.filename() == "..")
    throw InputError(where, "the " + what + " output must name a file, not a folder");
  std::error_code ec;
  if (fs::is_directory(p, ec)) throw InputError(where, "the " + what + " output is a folder");
  const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  if (!fs::is_directory(dir, ec))
    throw InputError(where, "the " + what + " output's folder \"" + dir.string() + "\" does not exist");
  // Can a file be created there? (Permission bits do not say it for root, nor for read-only
  // mounts: try.)
  const fs::path probe = temp_path_beside(p, ".probe-");
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0600);
  if (fd < 0)
    throw EnvironmentError(path + ": cannot create the " + what + " output in \"" + dir.string() +
                           "\": " + std::strerror(errno));
  ::close(fd);
  fs::remove(probe, ec);
}

void OutputTransaction::add(const std::string& path, const std::string& what) {
  check_output_path(path, what);
  // Two outputs of one name would overwrite each other (-o x.exr --checkpoint x.exr).
  std::error_code ec;
  const fs::path canonical = fs::weakly_canonical(path, ec);
  for (const std::string& other : paths_)
    if (other == path || (!ec && fs::weakly_canonical(other, ec) == canonical))
      throw InputError(SourceLocation{path, ""}, "the " + what + " output is the same file as another output");
  paths_.push_back(path);
}

void OutputTransaction::commit(const std::vector<Writer>& writers) {
  if (writers.size() != paths_.size()) throw std::invalid_argument("OutputTransaction: one writer per output");
  std::vector<fs::path> temps;
  const auto discard = [&] {
    std::error_code ignored;
    for (const fs::path& t : temps) fs::remove(t, ignored);
  };
  for (size_t i = 0; i < paths_.size(); ++i) {
    temps.push_back(temp_path_beside(paths_[i], ".tmp-"));
    try {
      writers[i](temps.back().string());
      // On disk before the rename: after a crash or power loss the name holds the whole new
      // file or the old one, never an empty one.
      const int fd = ::open(temps.back().c_str(), O_RDONLY);
      if (fd < 0 || ::fsync(fd) != 0) {
        const std::string why = std::strerror(errno);
        if (fd >= 0) ::close(fd);
        throw std::runtime_error("cannot flush " + temps.back().string() + ": " + why);
      }
      ::close(fd);
    } catch (const std::exception& e) {
      discard();
      throw EnvironmentError(paths_[i] + ": cannot write (nothing was replaced): " + e.what());
    }
  }
  for (size_t i = 0; i < paths_.size(); ++i) {
    std::error_code ec;
    fs::rename(temps[i], paths_[i], ec);
    if (ec) {
      // Renames within one folder fail only for reasons that hit the first one too; if an
      // earlier one succeeded, what was renamed stays (each is complete).
      discard();
      throw EnvironmentError(paths_[i] + ": cannot move the finished file into place: " + ec.message());
    }
  }
}

}  // namespace caligo
