// Grid files, in-process. By the input's first bytes:
//  - NanoVDB ("NanoVDB0"): listed, described (vdb_print's view) and loaded as a volume with
//    its first float grid as density and its first vec3s grid as color: segment parsing,
//    validation (pointers, checksums) and the VolumeGrid built on top;
//  - OpenVDB (its magic number): the layout checks that run before OpenVDB reads a file.
//    OpenVDB itself lives in the caligo_vdb.so plugin and is not fuzzed here (an
//    uninstrumented library of ~1M lines behind dlopen; a crash in it would still be found,
//    but blindly and slowly);
//  - anything else: a dense float32 file, dims (1..16)^3 from the first 3 bytes, the rest
//    the values (a size mismatch is one of the errors it must report).
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

#include "fuzz_support.h"
#include "grids/grid_io.h"
#include "grids/grid_io_internal.h"

namespace {

const caligo::SourceLocation kWhere{"fuzz.json", "/volumes/0/file"};

void read_nanovdb(const std::string& path) {
  caligo::GridChannels channels;
  for (const caligo::GridEntry& e : caligo::list_nvdb_grids(path, kWhere)) {
    if (e.type == "float" && channels.density == "density") channels.density = e.name;
    if (e.type == "vec3s" && !channels.color) channels.color = e.name;
  }
  caligo::describe_grid_file(path);
  caligo::load_grid_file(path, channels, kWhere);
}

void read_dense(const uint8_t* data, size_t size) {
  if (size < 3) return;
  caligo::DenseGridLayout layout;
  for (int a = 0; a < 3; ++a) layout.dims[size_t(a)] = 1 + data[a] % 16;
  layout.voxel_size = 0.25f;
  const std::string path = caligo::fuzz::input_file(data + 3, size - 3, ".raw");
  caligo::read_dense_file(path, layout, kWhere);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static constexpr unsigned char kNanoVdb[8] = {'N', 'a', 'n', 'o', 'V', 'D', 'B', '0'};
  static constexpr unsigned char kOpenVdb[8] = {0x20, 0x42, 0x44, 0x56, 0, 0, 0, 0};
  const bool nanovdb = size >= 8 && std::memcmp(data, kNanoVdb, 8) == 0;
  const bool openvdb = size >= 8 && std::memcmp(data, kOpenVdb, 8) == 0;
  caligo::fuzz::expect_value_or_input_error([&] {
    if (nanovdb)
      read_nanovdb(caligo::fuzz::input_file(data, size, ".nvdb"));
    else if (openvdb)
      caligo::check_vdb_layout(caligo::fuzz::input_file(data, size, ".vdb"), kWhere);
    else
      read_dense(data, size);
  });
  return 0;
}
