// Writes a file so that readers see either the old content or the complete new content, never a
// partial file (a crashed or interrupted render must not leave a truncated image behind).
#pragma once

#include <filesystem>
#include <functional>
#include <string>

namespace caligo {

// A fresh name in `target`'s folder: "." + its name + `tag` + pid-counter + its extension
// (unique within the process through the counter, across processes through the pid), so that
// writers choosing a codec by extension still work.
std::filesystem::path temp_path_beside(const std::filesystem::path& target, const char* tag);

// Flushes a written file to the disk (fsync), so that after a crash or power loss a name that
// was renamed onto it holds the whole file. Throws EnvironmentError naming `what_for`.
void flush_to_disk(const std::filesystem::path& file, const std::string& what_for);

// Temporaries that a killed caligo left in `dir` (regular files named exactly as
// temp_path_beside names them, ".NAME.tmp-PID-N.EXT", untouched for an hour, whose PID is no
// live process): removed, best effort. Called when an output in that folder is planned.
void remove_stale_temporaries(const std::filesystem::path& dir);

// Calls write(temp_path) with a temporary beside `path` (temp_path_beside: same file system,
// so the rename is atomic on POSIX), flushes it and renames it over `path`. If any step fails
// the temporary is removed and `path` is untouched: an InputError or std::invalid_argument from
// `write` propagates as it is, any other failure becomes an EnvironmentError naming `path`
// ("cannot write ... (nothing was replaced): why"). Concurrent calls get distinct temporaries,
// so concurrent writers to one path leave one complete file.
void write_file_atomically(const std::string& path,
                           const std::function<void(const std::string& temp_path)>& write);

// The reason in a write failure's message: what follows its last "(nothing was replaced): ",
// so that a writer that writes atomically itself, called on a transaction's temporary, is
// reported under the final name alone.
std::string write_failure_reason(const std::exception& e);

}  // namespace caligo
