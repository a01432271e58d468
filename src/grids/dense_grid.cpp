// Dense input made sparse: the seed's "dense grids can be made sparse on load". The array is
// cut into 8^3 blocks; values within the tolerance of 0 become background, and blocks left
// without an active voxel are dropped, so empty space costs neither memory nor marching.
#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>

#include "core/parallel.h"
#include "grids/grid_io.h"
#include "grids/grid_io_internal.h"

namespace caligo {
namespace {

constexpr uint64_t kMaxDenseVoxels = uint64_t(1) << 31;

uint64_t voxel_count(const std::array<int, 3>& d) { return uint64_t(d[0]) * uint64_t(d[1]) * uint64_t(d[2]); }

int blocks_along(int n) { return (n + kBlockDim - 1) / kBlockDim; }

}  // namespace

SparseFloatGrid dense_to_sparse(const std::vector<float>& values, const DenseGridLayout& layout,
                                float zero_tolerance) {
  const std::array<int, 3>& d = layout.dims;
  const int bx = blocks_along(d[0]), by = blocks_along(d[1]), bz = blocks_along(d[2]);
  // One pointer per block (8 bytes), a block only where data is: a 2 KB slot per block would
  // cost as much memory again as the dense input.
  std::vector<std::unique_ptr<SparseBlock>> slots(size_t(bx) * by * bz);
  parallel_for(int(slots.size()), [&](int s) {
    const int ib = s % bx, jb = (s / bx) % by, kb = s / (bx * by);
    SparseBlock block{{ib * kBlockDim, jb * kBlockDim, kb * kBlockDim}, {}};
    bool any = false;
    for (int x = 0; x < kBlockDim; ++x)
      for (int y = 0; y < kBlockDim; ++y)
        for (int z = 0; z < kBlockDim; ++z) {
          const int i = block.origin[0] + x, j = block.origin[1] + y, k = block.origin[2] + z;
          float v = 0.0f;
          if (i < d[0] && j < d[1] && k < d[2]) v = values[(size_t(k) * d[1] + j) * d[0] + i];
          if (std::abs(v) <= zero_tolerance) v = 0.0f;
          block.values[size_t(block_offset(x, y, z))] = v;
          any |= v != 0.0f;
        }
    if (any) slots[size_t(s)] = std::make_unique<SparseBlock>(block);
  });
  SparseFloatGrid grid;
  grid.name = "density";
  grid.voxel_size = layout.voxel_size;
  grid.origin = layout.origin + Vec3(0.5f * layout.voxel_size);
  for (const std::unique_ptr<SparseBlock>& slot : slots)
    if (slot) grid.blocks.push_back(*slot);
  return grid;
}

SparseFloatGrid read_dense_file(const std::string& path, const DenseGridLayout& layout,
                                const SourceLocation& where) {
  const std::array<int, 3>& d = layout.dims;
  if (d[0] <= 0 || d[1] <= 0 || d[2] <= 0)
    throw_grid_file_error(path, where, "dense grid dimensions must be positive");
  if (voxel_count(d) > kMaxDenseVoxels)
    throw_grid_file_error(path, where, "dense grid dimensions exceed 2^31 voxels");
  if (!(layout.voxel_size > 0.0f) || !std::isfinite(layout.voxel_size))
    throw_grid_file_error(path, where, "dense grid voxel size must be positive");
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw_grid_file_error(path, where, "no such dense grid file");
  const uint64_t expected = voxel_count(d) * sizeof(float);
  const uint64_t size = std::filesystem::file_size(path, ec);
  if (ec || size != expected)
    throw_grid_file_error(path, where,
                          "dense grid file holds " + std::to_string(size) + " bytes; " +
                              std::to_string(d[0]) + "x" + std::to_string(d[1]) + "x" + std::to_string(d[2]) +
                              " float32 values need " + std::to_string(expected));
  std::vector<float> values(voxel_count(d));
  std::ifstream in(path, std::ios::binary);
  if (!in.read(reinterpret_cast<char*>(values.data()), std::streamsize(expected)))
    throw_grid_file_error(path, where, "cannot read the dense grid file");
  static_assert(std::endian::native == std::endian::little, "dense grids are read as little-endian floats");
  for (size_t n = 0; n < values.size(); ++n)
    if (!std::isfinite(values[n]))
      throw_grid_file_error(path, where,
                            "dense grid holds a non-finite value at voxel (" + std::to_string(n % d[0]) +
                                ", " + std::to_string(n / d[0] % d[1]) + ", " +
                                std::to_string(n / (size_t(d[0]) * d[1])) + ")");
  return dense_to_sparse(values, layout);
}

std::shared_ptr<const VolumeGrid> load_dense_grid(const std::string& path, const DenseGridLayout& layout,
                                                  const SourceLocation& where) {
  NanoGrids grids{sparse_to_nanovdb(read_dense_file(path, layout, where)), std::nullopt, std::nullopt,
                  std::nullopt};
  return make_volume_grid(std::move(grids), where);
}

std::shared_ptr<const VolumeGrid> dense_values_grid(const std::vector<float>& values, const DenseGridLayout& layout,
                                                   const SourceLocation& where) {
  NanoGrids grids{sparse_to_nanovdb(dense_to_sparse(values, layout)), std::nullopt, std::nullopt, std::nullopt};
  return make_volume_grid(std::move(grids), where);
}

}  // namespace caligo
