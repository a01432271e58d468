// Errors that say where the problem is. An InputError is the user's fault (bad scene,
// mesh or command line: exit code 2); anything else escaping main is ours (exit code 1).
#pragma once

#include <algorithm>
#include <stdexcept>
#include <string>
#include <string_view>

#include "core/message_text.h"

namespace caligo {

// Where in the input something went wrong: a file and, for JSON, an RFC 6901 pointer
// such as "/lights/2/intensity". Either part may be empty.
struct SourceLocation {
  std::string file;
  std::string json_path;

  // Both parts as a message shows them: control characters escaped, a long file name or
  // pointer token (a 1 MB key) abbreviated (core/message_text.h).
  std::string to_string() const {
    const std::string f = printable_for_message(file, kMessageFileBytes);
    std::string p;
    for (size_t start = 0; start < json_path.size();) {
      const size_t slash = std::min(json_path.find('/', start + 1), json_path.size());
      const std::string_view token = std::string_view(json_path).substr(start, slash - start);
      p += printable_for_message(token, kMessageTokenBytes);
      start = slash;
    }
    if (f.empty()) return p;
    if (p.empty()) return f;
    return f + ": " + p;
  }
};

class InputError : public std::runtime_error {
 public:
  InputError(SourceLocation where, const std::string& what)
      : std::runtime_error(where.to_string().empty() ? what : where.to_string() + ": " + what),
        where_(std::move(where)) {}
  explicit InputError(const std::string& what) : std::runtime_error(what) {}
  const SourceLocation& where() const { return where_; }

 private:
  SourceLocation where_;
};

// The machine's fault, not the input's nor ours: an output that cannot be written (read-only
// folder, permission, disk full, I/O error). Exit code 3; the message names the file.
class EnvironmentError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

inline constexpr int kExitInputError = 2;
inline constexpr int kExitInternalError = 1;
inline constexpr int kExitEnvironmentError = 3;
// A check that ran and failed: `compare` above --max-rmse, or an image holding NaN or Inf.
inline constexpr int kExitCheckFailed = 4;
// A render stopped by SIGINT or SIGTERM after saving its checkpoint and partial image: 128 + the
// signal's number, as shells report a process the signal killed.
inline constexpr int kExitInterruptedBase = 128;

}  // namespace caligo
