// A folder a command writes its outputs into (the real-time frames, bench-table's tables):
// made when missing (its parent must exist), and removed again, if still empty, unless the
// command's outputs were committed (keep()). An existing folder is never removed.
#pragma once

#include <string>

namespace caligo {

class OutputFolder {
 public:
  // InputError when `path` is a file or its parent is missing; EnvironmentError when it cannot
  // be made.
  explicit OutputFolder(const std::string& path);
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  void keep() { created_.clear(); }

 private:
  std::string created_;  // the folder this command made, until keep()
};

}  // namespace caligo
