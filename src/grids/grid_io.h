// Grid files: OpenVDB `.vdb` and NanoVDB `.nvdb` volumes read into a VolumeGrid (rendering
// works on NanoVDB, as Cycles does: OpenVDB grids are converted on load), dense raw float
// arrays made sparse on load, grid files written (by the generator), and a vdb_print-like
// description of a file. No OpenVDB or NanoVDB header is included here: only
// grid_vdb_read.cpp and grid_vdb_write.cpp compile OpenVDB, and they form the caligo_vdb.so
// plugin, loaded by the first call that needs OpenVDB (vdb_plugin.h).
//
// Every problem with a file (missing, unreadable, wrong magic, truncated or corrupt, missing
// grid, wrong grid type, absurd size) is an InputError that names the file and `where` (the
// scene's JSON pointer); OpenVDB's and NanoVDB's own exceptions never escape.
// Thread safety: all functions may be called concurrently.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/bounds.h"
#include "core/error.h"
#include "grids/sparse_float_grid.h"
#include "grids/volume_grid.h"

namespace caligo {

// The grid names a volume reads. `density` is required. An optional channel left unset uses
// the conventional name when the file has it (temperature: "temperature"; flame: "flame",
// then "heat"; color: "Cd"); a channel named explicitly must exist.
struct GridChannels {
  std::string density = "density";
  std::optional<std::string> temperature, flame, color;
};

// A .vdb or .nvdb file, chosen by extension and confirmed by the file's magic bytes (a file
// with another extension is recognised by its magic alone). Density, temperature and flame
// must be float grids (double grids are converted), color a vec3 grid.
std::shared_ptr<const VolumeGrid> load_grid_file(const std::string& path, const GridChannels& channels,
                                                 const SourceLocation& where);

// A dense grid: a raw little-endian float32 array, x fastest, then y, then z, of exactly
// dims.x * dims.y * dims.z values. The array covers the world box
// [origin, origin + voxel_size * dims] (origin is the box's minimum corner, so voxel (i, j, k)
// has its centre at origin + voxel_size * (i + 0.5, j + 0.5, k + 0.5)).
struct DenseGridLayout {
  std::array<int, 3> dims{0, 0, 0};
  float voxel_size = 1.0f;
  Vec3 origin;
};

inline constexpr float kDenseZeroTolerance = 1e-6f;  // |value| at or below this is empty space

// Made sparse on load: values within kDenseZeroTolerance of 0 become inactive background and
// 8^3 blocks without an active voxel are not stored. The density grid is named "density".
std::shared_ptr<const VolumeGrid> load_dense_grid(const std::string& path, const DenseGridLayout& layout,
                                                  const SourceLocation& where);
// The same for values in memory (a scene's inline "values"; pbrt-v4's uniformgrid): finite, as
// many as the layout's voxels, x fastest.
std::shared_ptr<const VolumeGrid> dense_values_grid(const std::vector<float>& values, const DenseGridLayout& layout,
                                                   const SourceLocation& where);
// The sparse form of a dense file (validated as above; non-finite values are errors).
SparseFloatGrid read_dense_file(const std::string& path, const DenseGridLayout& layout,
                                const SourceLocation& where);
// `values` holds layout's dims product values, x fastest.
SparseFloatGrid dense_to_sparse(const std::vector<float>& values, const DenseGridLayout& layout,
                                float zero_tolerance = kDenseZeroTolerance);

// Writes the grids to a .vdb (OpenVDB, compressed) or .nvdb (NanoVDB, uncompressed, full
// checksum) file atomically: readers see the old file or the complete new one. Other
// extensions are an InputError.
void write_grid_file(const std::string& path, const std::vector<SparseFloatGrid>& grids);

// One grid of a file, in the spirit of OpenVDB's vdb_print.
struct GridInfo {
  std::string name;
  std::string type;  // value type: "float", "double", "vec3s", "int32", ...
  std::array<int, 3> index_min{0, 0, 0}, index_max{-1, -1, -1};  // active voxels, inclusive
  Bounds3 world_bounds;                                          // of the active voxels' cells
  Vec3 voxel_size;                                               // world units per voxel along each axis
  uint64_t active_voxels = 0;
  uint64_t active_leaves = 0;                  // 8^3 blocks holding active voxels
  uint64_t active_tiles = 0;                   // constant active tiles above the leaf level
  std::optional<double> min_value, max_value;  // of active values (vectors: their length)
  uint64_t memory_bytes = 0;  // OpenVDB: the grid's memory once read; NanoVDB: its buffer size
};

struct GridFileInfo {
  std::string path;
  std::string format;  // "OpenVDB" or "NanoVDB"
  uint64_t file_bytes = 0;
  std::vector<GridInfo> grids;
};

GridFileInfo describe_grid_file(const std::string& path);
// A table: one row per grid.
std::string format_grid_file_info(const GridFileInfo& info);

}  // namespace caligo
