// A guiding field's bytes -> GuidingField (what --resume reads from a guided checkpoint's training
// state): a field that loads must write the same bytes back, and sampling it anywhere must give
// a unit direction with a density its pdf agrees with, or an honest zero.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "fuzz_support.h"
#include "guiding/guiding_field.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  caligo::fuzz::expect_value_or_input_error([&] {
    const caligo::GuidingField field = caligo::GuidingField::from_bytes(bytes, "fuzz.field");
    if (field.to_bytes() != bytes) std::abort();
    const caligo::Bounds3& b = field.bounds();
    for (int i = 0; i < 8; ++i) {
      const caligo::Vec3 x{i & 1 ? b.hi.x : b.lo.x, i & 2 ? b.hi.y : b.lo.y, i & 4 ? b.hi.z : b.lo.z};
      const caligo::DirectionalTree* tree = field.at(x * 0.5f + b.center() * 0.5f);
      if (!tree) continue;
      float pdf = 0.0f;
      const caligo::Vec3 w = tree->sample({0.125f * float(i), 0.61f}, &pdf);
      if (std::isfinite(pdf) && pdf > 0.0f && std::abs(length(w) - 1.0f) > 1e-3f) std::abort();
      (void)tree->pdf(w);
    }
  });
  return 0;
}
