// Grid files: generated grids read back from .vdb and .nvdb (values, channels, description),
// and hostile files (empty, random, truncated, corrupt, missing or mistyped grids) rejected
// with errors that name the file. OpenVDB is used here only to make files of other types.
#include <gtest/gtest.h>

#include <openvdb/io/Stream.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <nanovdb/NanoVDB.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>

#include "core/rng.h"
#include "grids/grid_generate.h"
#include "grids/grid_io.h"
#include "grids/grid_io_internal.h"

namespace caligo {
namespace {

namespace fs = std::filesystem;

const SourceLocation kWhere{"scene.json", "/volumes/0/file"};

class GridIo : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("caligo-gridio-" + std::to_string(::getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  std::string write_bytes(const std::string& name, const std::string& bytes) const {
    std::ofstream(path(name), std::ios::binary) << bytes;
    return path(name);
  }

  static std::string slurp(const std::string& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }

  // Writes OpenVDB grids made by `make` (for types our writer never produces).
  std::string write_openvdb(const std::string& name, const openvdb::GridPtrVec& grids) const {
    openvdb::io::File file(path(name));
    file.write(grids);
    file.close();
    return path(name);
  }

  fs::path dir_;
};

// Every voxel of the sparse grid (active or not, in every block) reads back exactly.
void expect_same_values(const SparseFloatGrid& sparse, const NanoGridHandle& handle) {
  const nanovdb::NanoGrid<float>* grid = handle.grid<float>();
  ASSERT_NE(grid, nullptr);
  EXPECT_EQ(grid->activeVoxelCount(), sparse.active_voxels());
  EXPECT_EQ(grid->tree().nodeCount(0), sparse.blocks.size());
  auto acc = grid->getAccessor();
  for (const SparseBlock& b : sparse.blocks)
    for (int x = 0; x < kBlockDim; ++x)
      for (int y = 0; y < kBlockDim; ++y)
        for (int z = 0; z < kBlockDim; ++z) {
          const nanovdb::Coord ijk(b.origin[0] + x, b.origin[1] + y, b.origin[2] + z);
          ASSERT_EQ(acc.getValue(ijk), b.values[size_t(block_offset(x, y, z))]);
        }
  const nanovdb::Vec3d p = grid->indexToWorld(nanovdb::Vec3d(1, 2, 3));
  EXPECT_NEAR(p[0], sparse.origin.x + 1.0 * sparse.voxel_size, 1e-5);
  EXPECT_NEAR(p[1], sparse.origin.y + 2.0 * sparse.voxel_size, 1e-5);
  EXPECT_NEAR(p[2], sparse.origin.z + 3.0 * sparse.voxel_size, 1e-5);
}

TEST_F(GridIo, FireRoundTripsThroughVdbAndNvdb) {
  const std::vector<SparseFloatGrid> fire = generate_grids({GeneratedVolume::kFire, 32, 11});
  for (const char* name : {"fire.vdb", "fire.nvdb"}) {
    write_grid_file(path(name), fire);
    const NanoGrids grids = read_grid_channels(path(name), GridChannels{}, kWhere);
    expect_same_values(fire[0], grids.density);
    ASSERT_TRUE(grids.temperature.has_value()) << name;
    ASSERT_TRUE(grids.flame.has_value()) << name;
    EXPECT_FALSE(grids.color.has_value());
    expect_same_values(fire[1], *grids.temperature);
    expect_same_values(fire[2], *grids.flame);
  }
  // No temporary file is left beside the outputs.
  int files = 0;
  for (const auto& e : fs::directory_iterator(dir_)) files += e.is_regular_file();
  EXPECT_EQ(files, 2);
}

TEST_F(GridIo, SameSeedSameFileValuesOtherSeedDifferent) {
  write_grid_file(path("a.vdb"), generate_grids({GeneratedVolume::kSmoke, 24, 1}));
  write_grid_file(path("b.vdb"), generate_grids({GeneratedVolume::kSmoke, 24, 1}));
  write_grid_file(path("c.vdb"), generate_grids({GeneratedVolume::kSmoke, 24, 2}));
  const auto leaves = [&](const std::string& file) {
    const NanoGrids g = read_grid_channels(path(file), GridChannels{}, kWhere);
    const auto* grid = g.density.grid<float>();
    const auto* leaf = grid->tree().getFirstNode<0>();
    std::vector<float> values;
    for (uint32_t i = 0; i < grid->tree().nodeCount(0); ++i)
      for (uint32_t n = 0; n < 512; ++n) values.push_back(leaf[i].getValue(n));
    return values;
  };
  EXPECT_EQ(leaves("a.vdb"), leaves("b.vdb"));
  EXPECT_NE(leaves("a.vdb"), leaves("c.vdb"));
}

TEST_F(GridIo, DescribesVdbAndNvdbAlike) {
  const std::vector<SparseFloatGrid> cloud = generate_grids({GeneratedVolume::kCloud, 32, 4});
  float lo = kInfinity, hi = 0.0f;
  for (const SparseBlock& b : cloud[0].blocks)
    for (float v : b.values)
      if (v != 0.0f) lo = std::min(lo, v), hi = std::max(hi, v);
  std::vector<GridFileInfo> infos;
  for (const char* name : {"cloud.vdb", "cloud.nvdb"}) {
    write_grid_file(path(name), cloud);
    const GridFileInfo info = describe_grid_file(path(name));
    infos.push_back(info);
    EXPECT_EQ(info.file_bytes, fs::file_size(path(name)));
    ASSERT_EQ(info.grids.size(), 1u) << name;
    const GridInfo& g = info.grids[0];
    EXPECT_EQ(g.name, "density");
    EXPECT_EQ(g.type, "float");
    EXPECT_EQ(g.active_voxels, cloud[0].active_voxels());
    EXPECT_EQ(g.active_leaves, cloud[0].blocks.size());
    EXPECT_FLOAT_EQ(g.voxel_size.x, 0.125f);
    ASSERT_TRUE(g.min_value && g.max_value);
    EXPECT_FLOAT_EQ(float(*g.min_value), lo);
    EXPECT_FLOAT_EQ(float(*g.max_value), hi);
    EXPECT_GT(g.memory_bytes, cloud[0].blocks.size() * 512 * 4);
    EXPECT_LE(g.index_max[0], 31);
    EXPECT_GE(g.index_min[1], 0);
    EXPECT_GE(g.world_bounds.lo.y, -0.07f);  // cell bounds of voxels in the box
    EXPECT_LE(g.world_bounds.hi.x, 2.07f);
    const std::string table = format_grid_file_info(info);
    EXPECT_NE(table.find("density"), std::string::npos);
    EXPECT_NE(table.find(std::to_string(g.active_voxels)), std::string::npos);
  }
  // Both formats describe the same cells.
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(infos[0].grids[0].world_bounds.lo[a], infos[1].grids[0].world_bounds.lo[a], 1e-5f);
    EXPECT_NEAR(infos[0].grids[0].world_bounds.hi[a], infos[1].grids[0].world_bounds.hi[a], 1e-5f);
    EXPECT_EQ(infos[0].grids[0].index_min[a], infos[1].grids[0].index_min[a]);
    EXPECT_EQ(infos[0].grids[0].index_max[a], infos[1].grids[0].index_max[a]);
  }
  EXPECT_EQ(describe_grid_file(path("cloud.vdb")).format, "OpenVDB");
  EXPECT_EQ(describe_grid_file(path("cloud.nvdb")).format, "NanoVDB");
}

// The error is an InputError naming the file and the scene location, and mentioning `part`.
void expect_located_error(const std::function<void()>& f, const std::string& file, const std::string& part) {
  try {
    f();
    FAIL() << "no error; expected one mentioning " << part;
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(file), std::string::npos) << what;
    EXPECT_NE(what.find(part), std::string::npos) << what;
  }
}

void expect_unreadable(const std::string& file, const std::string& part) {
  expect_located_error([&] { read_grid_channels(file, GridChannels{}, kWhere); }, file, part);
  expect_located_error([&] { describe_grid_file(file); }, file, part);
}

TEST_F(GridIo, RejectsMissingEmptyAndRandomFiles) {
  expect_unreadable(path("missing.vdb"), "no such");
  expect_unreadable(write_bytes("empty.vdb", ""), "empty");
  std::string random(4096, '\0');
  Pcg32 rng(3, 4);
  for (char& c : random) c = char(rng.next_u32());
  expect_unreadable(write_bytes("random.vdb", random), "magic");
  expect_unreadable(write_bytes("random.nvdb", random), "magic");
  expect_unreadable(write_bytes("random.bin", random), "neither");
  // Right magic, garbage after it.
  expect_unreadable(write_bytes("garbage.vdb", std::string("\x20\x42\x44\x56\0\0\0\0", 8) + random),
                    "OpenVDB");
  expect_unreadable(write_bytes("garbage.nvdb", std::string("NanoVDB0", 8) + random), "NanoVDB");
  // The scene location is part of the message.
  expect_located_error([&] { read_grid_channels(path("missing.vdb"), GridChannels{}, kWhere); },
                       "missing.vdb", "scene.json: /volumes/0/file");
}

// Found by fuzz/grid_fuzz.cpp (a leak, seen under the asan preset): the message for another
// NanoVDB major version leaked the string nanovdb::Version::c_str() allocates.
TEST_F(GridIo, RejectsAnotherNanoVdbMajorVersionNamingIt) {
  write_grid_file(path("cloud.nvdb"), generate_grids({GeneratedVolume::kCloud, 8, 1}));
  std::string bytes = slurp(path("cloud.nvdb"));
  const uint32_t version = 31u << 21 | 1u << 10 | 2u;  // nanovdb::Version: major.minor.patch
  std::memcpy(bytes.data() + 8, &version, sizeof(version));  // after the 8-byte segment magic
  expect_unreadable(write_bytes("old.nvdb", bytes), "version 31.1.2 is not supported");
}

// Found by fuzz/grid_fuzz.cpp (UBSan): a codec number past the known ones was looked up in
// nanovdb::io::toStr's table out of bounds to name it.
TEST_F(GridIo, RejectsAnUnknownNanoVdbCodec) {
  write_grid_file(path("cloud.nvdb"), generate_grids({GeneratedVolume::kCloud, 8, 1}));
  std::string bytes = slurp(path("cloud.nvdb"));
  const uint16_t codec = 58;  // nanovdb::io::Codec has NONE, ZIP, BLOSC
  std::memcpy(bytes.data() + 14, &codec, sizeof(codec));  // magic (8), version (4), grid count (2)
  expect_unreadable(write_bytes("codec.nvdb", bytes), "unknown codec");
}

// Found by fuzz/grid_fuzz.cpp (UBSan, twice): a root offset pointing outside the grid was added
// to the tree's address (a pointer overflow) and bound to a reference (tree().root()) before
// the layout check looked at it; it is now checked as a number first.
TEST_F(GridIo, RejectsANanoVdbRootOutsideTheGrid) {
  write_grid_file(path("cloud.nvdb"), generate_grids({GeneratedVolume::kCloud, 8, 1}));
  std::string bytes = slurp(path("cloud.nvdb"));
  ASSERT_EQ(bytes.compare(16 + 176, 8, std::string("density\0", 8)), 0);  // one grid, "density"
  // Header (16), metadata (176), name (8), GridData (672), then the tree: the root's offset
  // is its mNodeOffset[3].
  const size_t root_offset_at = 16 + 176 + 8 + 672 + 3 * sizeof(uint64_t);
  const uint64_t far = 0x3042a5d66f71606eull;  // the fuzzer's
  std::memcpy(bytes.data() + root_offset_at, &far, sizeof(far));
  expect_unreadable(write_bytes("root.nvdb", bytes), "root outside the buffer");
}

// Found by fuzz/grid_fuzz.cpp (ASan, heap-buffer-overflow): a grid index other than 0 made
// GridHandle::grid() step past the end of the one-grid buffer looking for that grid.
TEST_F(GridIo, RejectsANanoVdbGridIndexOtherThanZero) {
  write_grid_file(path("cloud.nvdb"), generate_grids({GeneratedVolume::kCloud, 8, 1}));
  std::string bytes = slurp(path("cloud.nvdb"));
  // The grid's bytes start after the header (16), metadata (176) and name (8); its mGridIndex
  // follows mMagic, mChecksum (8 each), mVersion and mFlags (4 each).
  const uint32_t index = 1;
  std::memcpy(bytes.data() + 16 + 176 + 8 + 24, &index, sizeof(index));
  expect_unreadable(write_bytes("index.nvdb", bytes), "disagrees with its header");
}

TEST_F(GridIo, RejectsTruncatedAndCorruptFiles) {
  const auto cloud = generate_grids({GeneratedVolume::kCloud, 24, 8});
  for (const std::string ext : {".vdb", ".nvdb"}) {
    write_grid_file(path("whole" + ext), cloud);
    const std::string bytes = slurp(path("whole" + ext));
    for (double fraction : {0.02, 0.1, 0.5, 0.9, 0.999}) {
      const std::string name = "cut" + std::to_string(int(fraction * 1000)) + ext;
      expect_unreadable(write_bytes(name, bytes.substr(0, size_t(double(bytes.size()) * fraction))), name);
    }
    if (ext == ".vdb") {
      // Flipped bytes inside a compressed grid: OpenVDB has no checksum, so the read may
      // succeed with wrong values or fail, but it must fail as an InputError, never a crash.
      for (size_t at : {bytes.size() / 3, bytes.size() / 2, bytes.size() - 200}) {
        std::string corrupt = bytes;
        for (size_t i = at; i < at + 32; ++i) corrupt[i] = char(~corrupt[i]);
        const std::string name = write_bytes("corrupt" + std::to_string(at) + ".vdb", corrupt);
        try {
          read_grid_channels(name, GridChannels{}, kWhere);
        } catch (const InputError& e) {
          EXPECT_NE(std::string(e.what()).find(name), std::string::npos);
        }
      }
    }
    if (ext == ".nvdb") {
      // Flipped bytes in the voxel data: the full checksum catches them.
      std::string corrupt = bytes;
      for (size_t i = corrupt.size() / 2; i < corrupt.size() / 2 + 64; ++i) corrupt[i] = char(~corrupt[i]);
      expect_unreadable(write_bytes("corrupt.nvdb", corrupt), "corrupt");
    }
  }
}

TEST_F(GridIo, MissingGridsListWhatTheFileHas) {
  write_grid_file(path("smoke.nvdb"), generate_grids({GeneratedVolume::kSmoke, 16, 1}));
  write_grid_file(path("smoke.vdb"), generate_grids({GeneratedVolume::kSmoke, 16, 1}));
  for (const char* name : {"smoke.vdb", "smoke.nvdb"}) {
    GridChannels soot;
    soot.density = "soot";
    expect_located_error([&] { read_grid_channels(path(name), soot, kWhere); }, name, "\"density\" (float)");
    GridChannels heat;
    heat.temperature = "temperature";  // asked for by name: now required
    expect_located_error([&] { read_grid_channels(path(name), heat, kWhere); }, name, "no temperature grid");
    // Unasked optional channels are simply absent.
    const NanoGrids grids = read_grid_channels(path(name), GridChannels{}, kWhere);
    EXPECT_FALSE(grids.temperature || grids.flame || grids.color);
  }
}

TEST_F(GridIo, WrongGridTypesAreErrorsAndDoublesConvert) {
  openvdb::initialize();
  const auto transform = openvdb::math::Transform::createLinearTransform(0.5);
  auto vec = openvdb::Vec3SGrid::create();
  vec->setName("density");
  vec->tree().setValue(openvdb::Coord(1, 2, 3), openvdb::Vec3s(1, 0, 0));
  auto ints = openvdb::Int32Grid::create();
  ints->setName("density");
  ints->tree().setValue(openvdb::Coord(1, 2, 3), 7);
  auto doubles = openvdb::DoubleGrid::create();
  doubles->setName("density");
  doubles->setTransform(transform);
  doubles->tree().setValue(openvdb::Coord(1, 2, 3), 0.25);
  doubles->tree().setValue(openvdb::Coord(40, -9, 3), 2.5);
  auto color = openvdb::FloatGrid::create();  // a float grid where a colour belongs
  color->setName("Cd");
  color->tree().setValue(openvdb::Coord(0, 0, 0), 1.0f);

  expect_located_error([&] { read_grid_channels(write_openvdb("vec.vdb", {vec}), GridChannels{}, kWhere); },
                       "vec.vdb", "holds vec3s values; expected a float grid");
  expect_located_error([&] { read_grid_channels(write_openvdb("int.vdb", {ints}), GridChannels{}, kWhere); },
                       "int.vdb", "int32");
  expect_located_error(
      [&] {
        read_grid_channels(write_openvdb("cd.vdb", {doubles->deepCopyGrid(), color}), GridChannels{}, kWhere);
      },
      "cd.vdb", "color grid \"Cd\" holds float values");

  const NanoGrids grids = read_grid_channels(write_openvdb("double.vdb", {doubles}), GridChannels{}, kWhere);
  const auto* grid = grids.density.grid<float>();
  ASSERT_NE(grid, nullptr);
  auto acc = grid->getAccessor();
  EXPECT_EQ(acc.getValue(nanovdb::Coord(1, 2, 3)), 0.25f);
  EXPECT_EQ(acc.getValue(nanovdb::Coord(40, -9, 3)), 2.5f);
  EXPECT_EQ(grid->activeVoxelCount(), 2u);
  EXPECT_DOUBLE_EQ(grid->voxelSize()[0], 0.5);
}

TEST_F(GridIo, ExtensionAndMagicMustAgree) {
  write_grid_file(path("real.nvdb"), generate_grids({GeneratedVolume::kCloud, 8, 1}));
  fs::copy_file(path("real.nvdb"), path("fake.vdb"));
  fs::copy_file(path("real.nvdb"), path("noext"));
  expect_unreadable(path("fake.vdb"), "not an OpenVDB file");
  EXPECT_NO_THROW(read_grid_channels(path("noext"), GridChannels{}, kWhere));  // sniffed
  EXPECT_THROW(write_grid_file(path("out.exr"), generate_grids({GeneratedVolume::kCloud, 8, 1})), InputError);
  EXPECT_FALSE(fs::exists(path("out.exr")));
}

}  // namespace
}  // namespace caligo

namespace caligo {
namespace {

TEST_F(GridIo, LoadsVolumeGridsFromFilesAndDenseArrays) {
  const std::vector<SparseFloatGrid> fire = generate_grids({GeneratedVolume::kFire, 24, 2});
  write_grid_file(path("fire.nvdb"), fire);
  const auto grid = load_grid_file(path("fire.nvdb"), GridChannels{}, kWhere);
  EXPECT_TRUE(grid->has_temperature());
  EXPECT_TRUE(grid->has_flame());
  EXPECT_FALSE(grid->has_color());
  EXPECT_EQ(grid->statistics().active_voxels, fire[0].active_voxels());
  EXPECT_FLOAT_EQ(grid->voxel_size(), fire[0].voxel_size);

  const DenseGridLayout layout{{16, 8, 8}, 0.5f, Vec3(0.0f)};
  std::vector<float> values(16 * 8 * 8, 0.0f);
  values[(4 * 8 + 4) * 16 + 12] = 0.75f;  // voxel (12, 4, 4), inside the second block along x
  std::ofstream(path("d.raw"), std::ios::binary)
      .write(reinterpret_cast<const char*>(values.data()), 16 * 8 * 8 * 4);
  const auto dense = load_dense_grid(path("d.raw"), layout, kWhere);
  EXPECT_EQ(dense->statistics().active_voxels, 1u);
  EXPECT_EQ(dense->statistics().blocks, 1u);
  EXPECT_FLOAT_EQ(dense->statistics().max_value, 0.75f);
}

}  // namespace
}  // namespace caligo

namespace caligo {
namespace {

// Random byte changes and cuts of a valid file: each read either succeeds or is an InputError
// naming the file; none may crash the process (OpenVDB does crash on some of these, which the
// read in a child process catches).
TEST_F(GridIo, MutatedFilesNeverCrash) {
  for (const std::string ext : {".vdb", ".nvdb"}) {
    write_grid_file(path("src" + ext), generate_grids({GeneratedVolume::kFire, 16, 1}));
    const std::string bytes = slurp(path("src" + ext));
    Pcg32 rng(2024, ext.size());
    int errors = 0;
    for (int trial = 0; trial < 24; ++trial) {
      std::string b = bytes;
      for (uint32_t f = 0, n = 1 + rng.next_u32() % 8; f < n; ++f)
        b[rng.next_u32() % b.size()] = char(rng.next_u32());
      if (trial % 5 == 0) b.resize(rng.next_u32() % b.size());
      // Appended rather than "m" + to_string(...): g++ 12 warns falsely (-Wrestrict) on that form.
      std::string file = "m";
      file += std::to_string(trial);
      file += ext;
      const std::string name = write_bytes(file, b);
      try {
        read_grid_channels(name, GridChannels{}, kWhere);
        describe_grid_file(name);
      } catch (const InputError& e) {
        ++errors;
        EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
      }
    }
    EXPECT_GT(errors, 12) << ext;  // most mutations are detected
  }
}

// A file written as a stream (openvdb::io::Stream: no grid offsets) and cut short: OpenVDB
// read it without complaint, with the missing bytes as whatever memory held (different values
// from run to run). Each cut is refused, naming the file; the whole file reads.
TEST_F(GridIo, TruncatedStreamWrittenFilesAreRefused) {
  openvdb::initialize();
  auto grid = openvdb::FloatGrid::create(0.0f);
  grid->setName("density");
  grid->setTransform(openvdb::math::Transform::createLinearTransform(0.1));
  for (int i = 0; i < 4000; ++i) grid->tree().setValue(openvdb::Coord(i % 20, (i / 20) % 20, i / 400), 0.5f + 0.001f * float(i % 97));
  {
    std::ofstream out(path("stream.vdb"), std::ios::binary);
    openvdb::io::Stream(out).write(openvdb::GridPtrVec{grid});
  }
  const std::string whole = slurp(path("stream.vdb"));
  EXPECT_NO_THROW(read_grid_channels(path("stream.vdb"), GridChannels{}, kWhere));
  // Cuts up to 200 bytes before the end. (A cut 17 bytes before it passed in this process but
  // is refused by the caligo binary, which loads OpenVDB once: this test links a second copy.)
  for (size_t cut = 200; cut + 200 < whole.size(); cut += (whole.size() - 400) / 40) {
    const double fraction = double(cut) / double(whole.size());
    const std::string name = write_bytes("cut" + std::to_string(cut) + ".vdb", whole.substr(0, cut));
    try {
      read_grid_channels(name, GridChannels{}, kWhere);
      ADD_FAILURE() << "a stream-written file cut at " << fraction << " was read";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace caligo
