#include "realtime/frame_light.h"

#include "core/overloaded.h"

namespace caligo {

std::optional<ShadedLight> shaded_light(const Light& light) {
  using Shaded = std::optional<ShadedLight>;
  return std::visit(Overloaded{[](const PointLight& l) -> Shaded { return l; },
                               [](const SpotLight& l) -> Shaded { return l; },
                               [](const BoxLight& l) -> Shaded { return l; },
                               [](const DirectionalLight& l) -> Shaded { return l; },
                               [](const SphereLight&) -> Shaded { return std::nullopt; },
                               [](const QuadLight&) -> Shaded { return std::nullopt; },
                               [](const TriangleLight&) -> Shaded { return std::nullopt; },
                               [](const EnvironmentLight&) -> Shaded { return std::nullopt; }},
                    light);
}

}  // namespace caligo
