// Errors that say where the problem is. An InputError is the user's fault (bad scene,
// mesh or command line: exit code 2); anything else escaping main is ours (exit code 1).
#pragma once

#include <stdexcept>
#include <string>

namespace caligo {

// Where in the input something went wrong: a file and, for JSON, an RFC 6901 pointer
// such as "/lights/2/intensity". Either part may be empty.
struct SourceLocation {
  std::string file;
  std::string json_path;

  std::string to_string() const {
    if (file.empty()) return json_path;
    if (json_path.empty()) return file;
    return file + ": " + json_path;
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

inline constexpr int kExitInputError = 2;
inline constexpr int kExitInternalError = 1;

}  // namespace caligo
