// pbrt-v4 scene text -> SceneDesc: the tokenizer, the parameter lists, every directive's
// conversion and then the scene parser on the result. Include and the files a scene names
// resolve against an empty folder, so they fail as missing files.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.h"
#include "scene/pbrt_import.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  caligo::fuzz::expect_value_or_input_error([&] {
    const std::string dir = caligo::fuzz::scratch_dir();
    caligo::parse_pbrt(caligo::convert_pbrt_text(text, "fuzz.pbrt", dir), "fuzz.pbrt", dir);
  });
  return 0;
}
