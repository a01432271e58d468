// grid_io's side of caligo_vdb.so: the OpenVDB functions of grid_io_internal.h, forwarded to the
// plugin, which is loaded on the first call (vdb_plugin.h).
#include <stdexcept>

#include "core/module_loader.h"
#include "grids/vdb_plugin.h"

namespace caligo {
namespace {

const VdbPluginApi& vdb_plugin() {
  static const VdbPluginApi& api = load_plugin<VdbPluginApi>(kVdbPluginName, kVdbPluginSymbol, kVdbPluginAbi,
                                                             "needed for OpenVDB files and grid conversion");
  return api;
}

}  // namespace

std::vector<GridEntry> list_vdb_grids(const std::string& path, const SourceLocation& where) {
  return vdb_plugin().list_grids(path, where);
}

std::vector<NanoGridHandle> read_vdb_grids(const std::string& path, const std::vector<GridRequest>& requests,
                                           const SourceLocation& where) {
  return vdb_plugin().read_grids(path, requests, where);
}

GridFileInfo describe_vdb_file(const std::string& path) { return vdb_plugin().describe_file(path); }

void write_vdb_file(const std::string& path, const std::vector<SparseFloatGrid>& grids) {
  vdb_plugin().write_file(path, grids);
}

NanoGridHandle sparse_to_nanovdb(const SparseFloatGrid& grid, bool full_checksum) {
  return vdb_plugin().sparse_to_nanovdb(grid, full_checksum);
}

}  // namespace caligo
