// Dense input made sparse: values at every voxel survive, empty blocks vanish, bad sizes are
// located errors.
#include <gtest/gtest.h>

#include <nanovdb/NanoVDB.h>

#include <filesystem>
#include <fstream>
#include <map>

#include "core/rng.h"
#include "grids/grid_io.h"
#include "grids/grid_io_internal.h"

namespace caligo {
namespace {

namespace fs = std::filesystem;

struct DenseFixture : ::testing::Test {
  void SetUp() override {
    dir = fs::temp_directory_path() / ("caligo-dense-" + std::to_string(::getpid()));
    fs::create_directories(dir);
  }
  void TearDown() override { fs::remove_all(dir); }
  std::string write(const std::string& name, const std::vector<float>& values) const {
    const std::string path = (dir / name).string();
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(values.data()), std::streamsize(values.size() * sizeof(float)));
    return path;
  }
  fs::path dir;
};

// 20 x 13 x 17 (no dimension a multiple of 8): mostly zeros, some tiny values (empty space
// too), the first 8^3 block entirely zero.
std::vector<float> test_values(const DenseGridLayout& layout) {
  const auto& d = layout.dims;
  std::vector<float> v(size_t(d[0]) * d[1] * d[2]);
  Pcg32 rng(7, 1);
  for (int k = 0; k < d[2]; ++k)
    for (int j = 0; j < d[1]; ++j)
      for (int i = 0; i < d[0]; ++i) {
        const float u = rng.next_float();
        float value = u < 0.6f ? 0.0f : (u < 0.65f ? 1e-8f : rng.next_float() * 3.0f + 0.01f);
        if (i < 8 && j < 8 && k < 8) value = 0.0f;
        v[(size_t(k) * d[1] + j) * d[0] + i] = value;
      }
  return v;
}

TEST_F(DenseFixture, SparseRoundTripKeepsEveryVoxel) {
  const DenseGridLayout layout{{20, 13, 17}, 0.1f, Vec3(-1.0f, 0.5f, 2.0f)};
  const std::vector<float> values = test_values(layout);
  const SparseFloatGrid sparse = read_dense_file(write("a.raw", values), layout, {});
  uint64_t nonzero = 0;
  for (float v : values) nonzero += v > kDenseZeroTolerance;
  EXPECT_EQ(sparse.active_voxels(), nonzero);
  std::map<std::array<int, 3>, const SparseBlock*> blocks;
  for (const SparseBlock& b : sparse.blocks) blocks[b.origin] = &b;
  EXPECT_EQ(blocks.count({0, 0, 0}), 0u);  // the all-zero block is not stored
  EXPECT_EQ(blocks.size(), sparse.blocks.size());
  EXPECT_EQ(blocks.size(), 3u * 2u * 3u - 1u);

  // Through NanoVDB: every voxel's value, and the world placement of voxel centres.
  const NanoGridHandle handle = sparse_to_nanovdb(sparse);
  const nanovdb::NanoGrid<float>* grid = handle.grid<float>();
  ASSERT_NE(grid, nullptr);
  EXPECT_EQ(grid->activeVoxelCount(), nonzero);
  auto acc = grid->getAccessor();
  const auto& d = layout.dims;
  for (int k = 0; k < d[2]; ++k)
    for (int j = 0; j < d[1]; ++j)
      for (int i = 0; i < d[0]; ++i) {
        const float in = values[(size_t(k) * d[1] + j) * d[0] + i];
        const float expected = in > kDenseZeroTolerance ? in : 0.0f;
        const nanovdb::Coord ijk(i, j, k);
        ASSERT_EQ(acc.getValue(ijk), expected) << i << " " << j << " " << k;
        ASSERT_EQ(acc.isActive(ijk), expected != 0.0f);
      }
  const nanovdb::Vec3d centre = grid->indexToWorld(nanovdb::Vec3d(0, 0, 0));
  EXPECT_NEAR(centre[0], -1.0 + 0.05, 1e-6);
  EXPECT_NEAR(centre[1], 0.5 + 0.05, 1e-6);
  EXPECT_NEAR(centre[2], 2.0 + 0.05, 1e-6);
}

void expect_error_naming(const std::string& path, const DenseGridLayout& layout, const std::string& part) {
  try {
    read_dense_file(path, layout, {"scene.json", "/volumes/0"});
    FAIL() << "no error for " << part;
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find("/volumes/0"), std::string::npos) << what;
    EXPECT_NE(what.find(part), std::string::npos) << what;
  }
}

TEST_F(DenseFixture, BadSizesAndValuesAreLocatedErrors) {
  const std::string path = write("b.raw", std::vector<float>(4 * 4 * 4, 1.0f));
  expect_error_naming(path, {{4, 4, 5}, 0.1f, {}}, "need 320");  // size mismatch
  expect_error_naming(path, {{4, 4, 3}, 0.1f, {}}, "bytes");
  expect_error_naming(path, {{0, 4, 4}, 0.1f, {}}, "positive");
  expect_error_naming(path, {{-4, -4, 4}, 0.1f, {}}, "positive");
  expect_error_naming(path, {{2048, 2048, 1024}, 0.1f, {}}, "2^31");
  expect_error_naming(path, {{4, 4, 4}, 0.0f, {}}, "voxel size");
  expect_error_naming((dir / "missing.raw").string(), {{4, 4, 4}, 0.1f, {}}, "no such");
  std::vector<float> nan(64, 1.0f);
  nan[5] = std::nanf("");
  expect_error_naming(write("nan.raw", nan), {{4, 4, 4}, 0.1f, {}}, "(1, 1, 0)");
}

}  // namespace
}  // namespace caligo
