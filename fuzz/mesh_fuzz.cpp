// A mesh file -> TriangleMesh through load_mesh, the scene's only way in: the format's parser,
// the checks around it, triangulation, node transforms and validate_mesh(). The file's
// extension (CALIGO_FUZZ_MESH_EXTENSION) picks the reader; ".gltf" also reads GLB, which
// the loader recognises by its magic. Inputs of odd size ask for degenerate triangles to be
// removed ("skip_degenerate"), even ones for the default (rejected).
#include <cstddef>
#include <cstdint>

#include "fuzz_support.h"
#include "scene/mesh_loader.h"

#ifndef CALIGO_FUZZ_MESH_EXTENSION
#error "define CALIGO_FUZZ_MESH_EXTENSION (\".obj\", \".gltf\", \".ply\" or \".dae\")"
#endif

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = caligo::fuzz::input_file(data, size, CALIGO_FUZZ_MESH_EXTENSION);
  const auto degenerate =
      size % 2 ? caligo::DegenerateTriangles::kRemove : caligo::DegenerateTriangles::kReject;
  caligo::fuzz::expect_value_or_input_error(
      [&] { caligo::load_mesh(path, {"fuzz.json", "/shapes/0/file"}, degenerate); });
  return 0;
}
