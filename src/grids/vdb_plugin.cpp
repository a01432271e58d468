// caligo_vdb.so's entry point: the table of grid_vdb_read.cpp's and grid_vdb_write.cpp's
// functions (see vdb_plugin.h).
#include "grids/vdb_plugin.h"

extern "C" __attribute__((visibility("default"))) const caligo::VdbPluginApi* caligo_vdb_plugin() {
  static const caligo::VdbPluginApi api{caligo::kVdbPluginAbi,     &caligo::list_vdb_grids,
                                        &caligo::read_vdb_grids,   &caligo::describe_vdb_file,
                                        &caligo::write_vdb_file,   &caligo::sparse_to_nanovdb};
  return &api;
}
