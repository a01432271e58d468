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

namespace {

struct PlacementKey {
  std::vector<float> operator()(const PointLight& l) const { return {0, l.position.x, l.position.y, l.position.z}; }
  std::vector<float> operator()(const SpotLight& l) const {
    return {1,           l.position.x,  l.position.y,  l.position.z, l.direction.x, l.direction.y,
            l.direction.z, l.cos_outer, l.up.x,        l.up.y,       l.up.z};
  }
  std::vector<float> operator()(const BoxLight& l) const {
    return {2,           l.position.x, l.position.y, l.position.z, l.direction.x, l.direction.y, l.direction.z,
            l.up.x,      l.up.y,       l.up.z,       l.half_width, l.half_height, l.range};
  }
  std::vector<float> operator()(const DirectionalLight& l) const {
    return {3, l.direction.x, l.direction.y, l.direction.z};
  }
};

}  // namespace

std::vector<float> placement_key(const ShadedLight& light) { return std::visit(PlacementKey{}, light); }

}  // namespace caligo
