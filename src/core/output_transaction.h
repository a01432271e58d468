// Everything one command writes, committed together (a render's EXR, PNG preview and
// checkpoint): each output is written to a temporary file beside its final path, and only when
// every one of them has been written are they renamed into place. If any write fails, every
// temporary file is removed and no existing output is replaced.
//
// Outputs are checked when they are added, before any work is done, so a bad -o fails in
// milliseconds rather than after an hour of rendering:
//   - an empty name, a path that is a directory, or a folder that does not exist: InputError;
//   - a folder where no file can be created (read-only, no permission): EnvironmentError;
//   - a path that is already an output of the transaction: InputError;
//   - a path that names one of the command's inputs (protect()): InputError naming both.
// Files are compared by identity (device and inode, symlinks followed), so a hard link or a
// symlink to an input is refused as well as the input's own name.
// Each file is flushed to disk (fsync) before the renames.
// Failures while writing (disk full, I/O errors) are EnvironmentErrors naming the file.
// Outputs may be written one at a time as the work produces them (stage(), e.g. the real-time
// command's frames) and renamed together at the end (commit()); a transaction destroyed before
// its commit removes what it staged. Copying one copies its plan, not its staged files.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <utility>
#include <string>
#include <vector>

namespace caligo {

class OutputTransaction {
 public:
  using Writer = std::function<void(const std::string& temp_path)>;

  // Checks `path` (see above) and remembers it; `what` names it in messages ("image").
  void add(const std::string& path, const std::string& what);
  // Marks a file the command reads (`what`: "scene file", "gobo image", ...): no output may be
  // the same file, except `may_replace` when given (a resumed checkpoint saved again). Throws
  // InputError when an output added before is. Files that do not exist are never matched.
  void protect(const std::string& path, const std::string& what, const std::string& may_replace = "");
  // Writes every added output with its writer (one per add, same order), then renames them all.
  // The writers get a temporary path with the final path's extension.
  void commit(const std::vector<Writer>& writers);
  // Writes output `index` (in add order) to its temporary now; on failure every staged file is
  // removed. commit() renames every output, which must all have been staged.
  void stage(size_t index, const Writer& writer);
  void commit();

  size_t size() const { return paths_.size(); }
  const std::string& path(size_t index) const { return paths_[index]; }

  OutputTransaction() = default;
  OutputTransaction(const OutputTransaction& other)
      : paths_(other.paths_), outputs_(other.outputs_), inputs_(other.inputs_), probed_(other.probed_) {}
  OutputTransaction& operator=(const OutputTransaction&) = delete;
  ~OutputTransaction();

 private:
  using FileId = std::optional<std::pair<unsigned long, unsigned long>>;  // device, inode
  struct Output {
    std::string path, canonical;
    FileId identity;  // when the file exists
  };
  struct Input {
    std::string path, what, may_replace, canonical;
    FileId identity;
  };
  void refuse_input(const Output& output, const std::string& what) const;

  void discard();

  std::vector<std::string> paths_;
  std::vector<Output> outputs_;
  std::vector<Input> inputs_;
  std::vector<std::string> probed_;  // folders already probed
  std::vector<std::string> temps_;  // per output: its staged temporary, or empty
};

}  // namespace caligo
