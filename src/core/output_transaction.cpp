#include "core/output_transaction.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

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
std::optional<std::pair<dev_t, ino_t>> identity(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return std::nullopt;
  return std::pair{st.st_dev, st.st_ino};
}

bool same_file(const std::string& a, const std::string& b) {
  const auto ia = identity(a);
  return ia && ia == identity(b);
}

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
  remove_stale_temporaries(p);
}

void OutputTransaction::add(const std::string& path, const std::string& what) {
  check_output_path(path, what);
  // Two outputs of one name would overwrite each other (-o x.exr --checkpoint x.exr).
  std::error_code ec;
  const fs::path canonical = fs::weakly_canonical(path, ec);
  for (const std::string& other : paths_)
    if (other == path || (!ec && fs::weakly_canonical(other, ec) == canonical) || same_file(other, path))
      throw InputError(SourceLocation{path, ""}, "the " + what + " output is the same file as another output");
  refuse_input(path, what);
  paths_.push_back(path);
}

void OutputTransaction::protect(const std::string& path, const std::string& what, const std::string& may_replace) {
  inputs_.push_back({path, what, may_replace});
  for (const std::string& output : paths_) refuse_input(output, "");
}

void OutputTransaction::refuse_input(const std::string& output, const std::string& what) const {
  std::error_code ec;
  const fs::path canonical = fs::weakly_canonical(output, ec);
  for (const Input& in : inputs_) {
    if (!in.may_replace.empty() && (in.may_replace == output || same_file(in.may_replace, output))) continue;
    std::error_code ec2;
    if (same_file(in.path, output) || (!ec && fs::weakly_canonical(in.path, ec2) == canonical))
      throw InputError(SourceLocation{output, ""}, "the " + (what.empty() ? std::string() : what + " ") +
                                                        "output is the " + in.what + " \"" + in.path +
                                                        "\" the command reads; choose another output name");
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
  if (!temps_[index].empty()) fs::remove(temps_[index]);
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
  } catch (const EnvironmentError&) {
    discard();
    throw;
  } catch (const std::exception& e) {
    discard();
    throw EnvironmentError(paths_[index] + ": cannot write (nothing was replaced): " + e.what());
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
