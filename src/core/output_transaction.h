// Everything one command writes, committed together (a render's EXR, PNG preview and
// checkpoint): each output is written to a temporary file beside its final path, and only when
// every one of them has been written are they renamed into place. If any write fails, every
// temporary file is removed and no existing output is replaced.
//
// Outputs are checked when they are added, before any work is done, so a bad -o fails in
// milliseconds rather than after an hour of rendering:
//   - an empty name, a path that is a directory, or a folder that does not exist: InputError;
//   - a folder where no file can be created (read-only, no permission): EnvironmentError;
//   - a path that is already an output of the transaction: InputError.
// Each file is flushed to disk (fsync) before the renames.
// Failures while writing (disk full, I/O errors) are EnvironmentErrors naming the file.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace caligo {

class OutputTransaction {
 public:
  using Writer = std::function<void(const std::string& temp_path)>;

  // Checks `path` (see above) and remembers it; `what` names it in messages ("image").
  void add(const std::string& path, const std::string& what);
  // Writes every added output with its writer (one per add, same order), then renames them all.
  // The writers get a temporary path with the final path's extension.
  void commit(const std::vector<Writer>& writers);

 private:
  std::vector<std::string> paths_;
};

// The check add() makes, alone.
void check_output_path(const std::string& path, const std::string& what);

}  // namespace caligo
