#include "output_folder.h"

#include <filesystem>
#include <system_error>

#include "core/error.h"

namespace caligo {

namespace fs = std::filesystem;

OutputFolder::OutputFolder(const std::string& path) {
  std::error_code ec;
  if (fs::exists(path, ec)) {
    if (!fs::is_directory(path, ec)) throw InputError(SourceLocation{path, ""}, "output exists and is not a folder");
    return;
  }
  fs::path folder(path);
  if (folder.filename().empty()) folder = folder.parent_path();  // "frames/"
  const fs::path parent = folder.parent_path().empty() ? "." : folder.parent_path();
  if (!fs::is_directory(parent, ec))
    throw InputError(SourceLocation{path, ""}, "the output folder's parent \"" + parent.string() + "\" does not exist");
  if (!fs::create_directory(path, ec)) throw EnvironmentError(path + ": cannot create the output folder: " + ec.message());
  created_ = path;
}

OutputFolder::~OutputFolder() {
  std::error_code ignored;
  if (!created_.empty()) fs::remove(created_, ignored);  // removes only an empty folder
}

}  // namespace caligo
