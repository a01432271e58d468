// The entry points of caligo_vdb.so, the plugin that keeps OpenVDB (with Boost iostreams,
// Blosc, log4cplus: ~30 ms and ~28 MB of process start-up) out of every run that reads no
// OpenVDB file and converts no grid (see core/module_loader.h). The plugin holds
// grid_vdb_read.cpp and grid_vdb_write.cpp; grid_io reaches their functions (declared in
// grid_io_internal.h) through this table (vdb_plugin_client.cpp). Host and plugin are built
// together: C++ types, and the InputErrors the functions throw, cross the boundary.
#pragma once

#include <string>
#include <vector>

#include "grids/grid_io_internal.h"

namespace caligo {

struct VdbPluginApi {
  int abi_version;
  std::vector<GridEntry> (*list_grids)(const std::string& path, const SourceLocation& where);
  std::vector<NanoGridHandle> (*read_grids)(const std::string& path, const std::vector<GridRequest>& requests,
                                            const SourceLocation& where);
  GridFileInfo (*describe_file)(const std::string& path);
  void (*write_file)(const std::string& path, const std::vector<SparseFloatGrid>& grids);
  NanoGridHandle (*sparse_to_nanovdb)(const SparseFloatGrid& grid, bool full_checksum);
};

inline constexpr int kVdbPluginAbi = 1;
inline constexpr const char* kVdbPluginName = "caligo_vdb";
inline constexpr const char* kVdbPluginSymbol = "caligo_vdb_plugin";

}  // namespace caligo
