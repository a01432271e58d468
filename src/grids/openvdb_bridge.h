// OpenVDB, for the two translation units that need it (grid_vdb_read.cpp and
// grid_vdb_write.cpp): each OpenVDB include costs seconds of compile time, so nothing else
// includes this header.
#pragma once

#include <openvdb/openvdb.h>

#include "grids/volume_grid_build.h"

namespace caligo {

// openvdb::initialize(), once per process (registers grid types for file reading).
void initialize_openvdb();

// The one OpenVDB-to-NanoVDB conversion (grid_vdb_read.cpp): min/max statistics, and a full
// checksum when `full_checksum` (files we write; loads need only the cheap partial one).
NanoGridHandle to_nanovdb(const openvdb::FloatGrid& grid, bool full_checksum);
NanoGridHandle to_nanovdb(const openvdb::Vec3SGrid& grid, bool full_checksum);

}  // namespace caligo
