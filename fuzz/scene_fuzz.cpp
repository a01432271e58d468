// Scene text (JSON) -> SceneDesc: the JSON reader's limits, every parser of scene keys, unit
// conversions and the generators a scene can ask for. Files the scene names (meshes, images,
// IES profiles, grids) resolve against an empty folder, so they fail as missing files.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.h"
#include "scene/scene_parser.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  caligo::fuzz::expect_value_or_input_error(
      [&] { caligo::parse_scene_text(text, "fuzz.json", caligo::fuzz::scratch_dir()); });
  return 0;
}
