// Writes a file so that readers see either the old content or the complete new content, never a
// partial file (a crashed or interrupted render must not leave a truncated image behind).
#pragma once

#include <functional>
#include <string>

namespace caligo {

// Calls write(temp_path) with a fresh temporary name in the same directory as `path` (so the
// final rename stays on one file system and is atomic on POSIX), then renames it over `path`.
// The temporary name ends with path's extension (".out.exr.tmp-<pid>-<n>.exr"), so writers that
// choose a codec by extension still work. If write or the rename throws, the temporary file is
// removed and the exception propagates; `path` is then untouched.
// Thread safety: concurrent calls get distinct temporary names.
void write_file_atomically(const std::string& path,
                           const std::function<void(const std::string& temp_path)>& write);

}  // namespace caligo
