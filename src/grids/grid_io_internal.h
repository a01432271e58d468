// The pieces of grid_io shared between its translation units (and its tests). OpenVDB types
// never appear here: grid_vdb_read.cpp and grid_vdb_write.cpp keep them to themselves.
#pragma once

#include <string>
#include <vector>

#include "core/error.h"
#include "grids/grid_io.h"
#include "grids/volume_grid_build.h"

namespace caligo {

enum class GridFileFormat { kOpenVdb, kNanoVdb };

// Decided by the extension (.vdb, .nvdb) and confirmed by the magic bytes; a file with
// another extension is recognised by its magic. Missing, unreadable or unrecognised files
// are InputErrors.
GridFileFormat grid_file_format(const std::string& path, const SourceLocation& where);

// InputError at `where` whose message starts with the file's name.
[[noreturn]] void throw_grid_file_error(const std::string& path, const SourceLocation& where,
                                        const std::string& what);

// A grid as a file lists it. Types use OpenVDB's value-type names for both formats:
// "float", "double", "int32", "vec3s", "vec3d", ...
struct GridEntry {
  std::string name;
  std::string type;
};

enum class GridValueKind { kFloat, kVec3 };

struct GridRequest {
  std::string name;
  GridValueKind kind;
};

// The grids the channels ask for, resolved against the file's list (missing or mistyped
// grids are InputErrors listing what the file has), then read.
NanoGrids read_grid_channels(const std::string& path, const GridChannels& channels,
                             const SourceLocation& where);

// OpenVDB files (grid_vdb_read.cpp, grid_vdb_write.cpp). Reading converts double grids to
// float and vec3d to vec3s, then each grid to NanoVDB.
// Header, version and grid descriptors checked against the file's size (vdb_layout.cpp).
// Returns whether the file has grid offsets (false: written as a stream, read sequentially).
bool check_vdb_layout(const std::string& path, const SourceLocation& where);
std::vector<GridEntry> list_vdb_grids(const std::string& path, const SourceLocation& where);
std::vector<NanoGridHandle> read_vdb_grids(const std::string& path, const std::vector<GridRequest>& requests,
                                           const SourceLocation& where);
GridFileInfo describe_vdb_file(const std::string& path);
void write_vdb_file(const std::string& path, const std::vector<SparseFloatGrid>& grids);
// Through an OpenVDB grid, so that every NanoVDB grid we make comes from one converter.
NanoGridHandle sparse_to_nanovdb(const SparseFloatGrid& grid, bool full_checksum = false);

// NanoVDB files (grid_nvdb.cpp): headers are parsed and bounded before anything is allocated,
// and every grid read is validated (pointers, checksum).
std::vector<GridEntry> list_nvdb_grids(const std::string& path, const SourceLocation& where);
std::vector<NanoGridHandle> read_nvdb_grids(const std::string& path, const std::vector<GridRequest>& requests,
                                            const SourceLocation& where);
GridFileInfo describe_nvdb_file(const std::string& path);
void write_nvdb_file(const std::string& path, const std::vector<SparseFloatGrid>& grids);

}  // namespace caligo
