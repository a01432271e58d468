// Writes a file so that readers see either the old content or the complete new content, never a
// partial file (a crashed or interrupted render must not leave a truncated image behind).
#pragma once

#include <filesystem>
#include <functional>
#include <string>

namespace caligo {

// Calls write(temp_path) with a fresh temporary name in the same directory as `path` (so the
// final rename stays on one file system and is atomic on POSIX), then renames it over `path`.
// The temporary name ends with path's extension (".out.exr.tmp-<pid>-<n>.exr"), so writers that
// choose a codec by extension still work. If write or the rename throws, the temporary file is
// removed and the exception propagates; `path` is then untouched.
// Thread safety: concurrent calls get distinct temporary names.
// A fresh name in `target`'s folder: "." + its name + `tag` + pid-counter + its extension
// (unique within the process through the counter, across processes through the pid).
std::filesystem::path temp_path_beside(const std::filesystem::path& target, const char* tag);

void write_file_atomically(const std::string& path,
                           const std::function<void(const std::string& temp_path)>& write);

}  // namespace caligo
