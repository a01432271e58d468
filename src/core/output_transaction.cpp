#include "core/output_transaction.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <optional>
#include <utility>
#include <system_error>

#include "core/atomic_file.h"
#include "core/error.h"

namespace caligo {
namespace {

namespace fs = std::filesystem;

// Device and inode after following symlinks; nullopt for a path that names no file (yet).
std::optional<std::pair<unsigned long, unsigned long>> identity(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return std::nullopt;
  return std::pair<unsigned long, unsigned long>{st.st_dev, st.st_ino};
}

bool same_file(const std::string& a, const std::string& b) {
  const auto ia = identity(a);
  return ia && ia == identity(b);
}

}  // namespace

namespace {

// The checks add() makes before the probe: the path names a file in an existing folder.
fs::path checked_folder(const std::string& path, const std::string& what) {
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
  return dir;
}

// Can a file be created in `dir`? (Permission bits do not say it for root, nor for read-only
// mounts: try.) Also clears what killed runs left there.
void probe_folder(const fs::path& dir, const std::string& path, const std::string& what) {
  const fs::path probe = temp_path_beside(fs::path(path), ".probe-");
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0600);
  if (fd < 0)
    throw EnvironmentError(path + ": cannot create the " + what + " output in \"" + dir.string() +
                           "\": " + std::strerror(errno));
  ::close(fd);
  std::error_code ec;
  fs::remove(probe, ec);
  remove_stale_temporaries(dir);
}

}  // namespace

void OutputTransaction::add(const std::string& path, const std::string& what) {
  const fs::path dir = checked_folder(path, what);
  std::error_code ec;
  const std::string canonical = fs::weakly_canonical(dir, ec).string();
  if (std::find(probed_.begin(), probed_.end(), canonical) == probed_.end()) {
    probe_folder(dir, path, what);
    probed_.push_back(canonical);
  }
  // Two outputs of one file would overwrite each other (-o x.exr --checkpoint x.exr).
  Output out{path, fs::weakly_canonical(path, ec).string(), identity(path)};
  if (ec) out.canonical.clear();
  for (const Output& other : outputs_)
    if (other.path == path || (!out.canonical.empty() && other.canonical == out.canonical) ||
        (out.identity && other.identity == out.identity))
      throw InputError(SourceLocation{path, ""}, "the " + what + " output is the same file as another output");
  refuse_input(out, what);
  outputs_.push_back(std::move(out));
  paths_.push_back(path);
}

void OutputTransaction::protect(const std::string& path, const std::string& what, const std::string& may_replace) {
  std::error_code ec;
  Input in{path, what, may_replace, fs::weakly_canonical(path, ec).string(), identity(path)};
  if (ec) in.canonical.clear();
  inputs_.push_back(std::move(in));
  for (const Output& output : outputs_) refuse_input(output, "");
}

void OutputTransaction::refuse_input(const Output& output, const std::string& what) const {
  for (const Input& in : inputs_) {
    if (!in.may_replace.empty() && (in.may_replace == output.path || same_file(in.may_replace, output.path))) continue;
    if ((in.identity && in.identity == output.identity) ||
        (!in.canonical.empty() && in.canonical == output.canonical))
      throw InputError(SourceLocation{output.path, ""},
                       "the " + (what.empty() ? std::string() : what + " ") + "output is the " + in.what + " \"" +
                           in.path + "\" the command reads; choose another output name");
  }
}

OutputTransaction::~OutputTransaction() { discard(); }

void OutputTransaction::discard() {
  std::error_code ignored;
  for (const std::string& t : temps_)
    if (!t.empty()) fs::remove(t, ignored);
  temps_.clear();
}

void OutputTransaction::stage(size_t index, const Writer& writer) {
  if (index >= paths_.size()) throw std::invalid_argument("OutputTransaction: no output " + std::to_string(index));
  temps_.resize(paths_.size());
  std::error_code ignored;
  if (!temps_[index].empty()) fs::remove(temps_[index], ignored);
  temps_[index] = temp_path_beside(paths_[index], ".tmp-").string();
  try {
    writer(temps_[index]);
    flush_to_disk(temps_[index], paths_[index]);
  } catch (const std::invalid_argument&) {
    discard();
    throw;
  } catch (const InputError&) {
    discard();
    throw;
  } catch (const std::exception& e) {
    discard();
    throw EnvironmentError(paths_[index] + ": cannot write (nothing was replaced): " + write_failure_reason(e));
  }
}

void OutputTransaction::commit(const std::vector<Writer>& writers) {
  if (writers.size() != paths_.size()) throw std::invalid_argument("OutputTransaction: one writer per output");
  for (size_t i = 0; i < paths_.size(); ++i) stage(i, writers[i]);
  commit();
}

void OutputTransaction::commit() {
  temps_.resize(paths_.size());
  for (const std::string& t : temps_)
    if (t.empty()) throw std::invalid_argument("OutputTransaction: commit before every output was staged");
  for (size_t i = 0; i < paths_.size(); ++i) {
    std::error_code ec;
    fs::rename(temps_[i], paths_[i], ec);
    if (ec) {
      // Renames within one folder fail only for reasons that hit the first one too; if an
      // earlier one succeeded, what was renamed stays (each is complete).
      for (size_t j = 0; j < i; ++j) temps_[j].clear();
      discard();
      throw EnvironmentError(paths_[i] + ": cannot move the finished file into place: " + ec.message());
    }
  }
  temps_.clear();
}

}  // namespace caligo
