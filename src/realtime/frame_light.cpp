#include "realtime/frame_light.h"

#include <type_traits>

namespace caligo {

// The light types ShadedLight holds pass through; every other one (area and environment
// lights, and any new type until the passes learn to shade it) is left to the path tracer.
std::optional<ShadedLight> shaded_light(const Light& light) {
  return std::visit(
      [](const auto& l) -> std::optional<ShadedLight> {
        if constexpr (std::is_constructible_v<ShadedLight, decltype(l)>)
          return ShadedLight(l);
        else
          return std::nullopt;
      },
      light);
}

}  // namespace caligo
