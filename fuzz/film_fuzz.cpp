// Checkpoint bytes -> Film (Film::from_bytes, what --resume and the MPI ranks read): a film
// that loads must resolve to an image of its resolution with finite sample counts, and its
// bytes must round-trip exactly (the CRC-32 and the header checks hold whatever the input).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "fuzz_support.h"
#include "render/film.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  caligo::fuzz::expect_value_or_input_error([&] {
    uint64_t key = 0;
    const caligo::Film film = caligo::Film::from_bytes(bytes, "fuzz.ckpt", &key);
    if (film.to_bytes(key) != bytes) std::abort();
    const caligo::Image image = film.resolve();
    if (image.width() != film.resolution().x || image.height() != film.resolution().y) std::abort();
  });
  return 0;
}
