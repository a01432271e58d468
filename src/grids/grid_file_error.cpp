#include "grids/grid_io_internal.h"

namespace caligo {

void throw_grid_file_error(const std::string& path, const SourceLocation& where, const std::string& what) {
  throw InputError(where, path + ": " + what);
}

}  // namespace caligo
