#include "realtime/frame_light.h"

#include <algorithm>
#include <type_traits>

#include "realtime/light_stand_ins.h"

namespace caligo {

// The light types ShadedLight holds pass through, those with a stand-in become it; any other
// (a new type, until the passes learn to shade it) is left to the path tracer.
std::vector<ShadedPart> shaded_lights(const Light& light, int environment_lights) {
  return std::visit(
      [environment_lights](const auto& l) -> std::vector<ShadedPart> {
        using T = std::decay_t<decltype(l)>;
        if constexpr (std::is_same_v<T, EnvironmentLight>) {
          std::vector<ShadedPart> suns;
          for (const EnvironmentSun& sun : environment_stand_ins(l, std::max(1, environment_lights)))
            suns.push_back({sun.light, sun.volumetric_scale});
          return suns;
        } else if constexpr (std::is_constructible_v<ShadedLight, T>) {
          return {{ShadedLight(l)}};
        } else if constexpr (requires { stand_in(l); }) {
          return {{ShadedLight(stand_in(l))}};
        } else {
          return {};
        }
      },
      light);
}

std::optional<ShadedLight> shaded_light(const Light& light) {
  if (std::holds_alternative<EnvironmentLight>(light)) return std::nullopt;
  std::vector<ShadedPart> one = shaded_lights(light, 1);
  if (one.empty()) return std::nullopt;
  return std::move(one.front().light);
}

std::vector<FrameLight> frame_lights(const SceneDesc& desc, const std::vector<Light>& posed, int environment_lights) {
  std::vector<FrameLight> out;
  size_t further = posed.size();  // the cache index of an environment's second and later suns
  for (size_t i = 0; i < posed.size(); ++i) {
    std::vector<ShadedPart> parts = shaded_lights(posed[i], environment_lights);
    for (size_t k = 0; k < parts.size(); ++k) {
      LightOptions options = desc.options(i);
      options.volumetric_intensity *= parts[k].volumetric_scale;
      out.push_back({std::move(parts[k].light), std::move(options), nullptr, k == 0 ? i : further++, i, int(i)});
    }
  }
  return out;
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
