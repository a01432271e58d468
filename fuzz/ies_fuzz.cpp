// IES LM-63 text -> IesProfile, then lookups: a parsed profile must evaluate to finite values
// in [0, 1] everywhere (the header's promise) and have a finite mean.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "fuzz_support.h"
#include "lights/ies.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  caligo::fuzz::expect_value_or_input_error([&] {
    const caligo::IesProfile profile = caligo::IesProfile::parse(text, "fuzz.ies");
    if (!std::isfinite(profile.mean())) std::abort();
    for (int v = 0; v <= 8; ++v)
      for (int h = 0; h <= 8; ++h) {
        const float value = profile.evaluate(float(v) * 0.125f * 3.14159265f, float(h) * 0.25f * 3.14159265f);
        if (!(value >= 0.0f && value <= 1.0f)) std::abort();
      }
  });
  return 0;
}
