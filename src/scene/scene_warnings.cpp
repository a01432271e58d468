#include "scene/scene_warnings.h"

#include <set>

#include "core/error.h"
#include "lights/light.h"
#include "media/medium_stack.h"

namespace caligo {

std::vector<std::string> priority_shadow_warnings(const SceneDesc& scene) {
  std::vector<std::string> warnings;
  if (scene.render.path.priority_shadows) return warnings;
  const Light* delta = nullptr;
  for (const Light& light : scene.lights)
    if (is_delta(light) && power(light) > 0.0f) {
      delta = &light;
      break;
    }
  if (!delta) return warnings;
  std::set<int> named;
  for (const ShapeDesc& shape : scene.shapes) {
    if (shape.material < 0 || size_t(shape.material) >= scene.materials.size()) continue;
    const Material& m = scene.materials[size_t(shape.material)];
    if (m.priority == kPriorityOff || !std::holds_alternative<DielectricBsdf>(m.bsdf)) continue;
    if (!named.insert(shape.material).second) continue;
    warnings.push_back("material \"" + printable_for_message(m.name, kMessageTokenBytes) + "\" (" + shape.where.to_string() +
                       ") is a priority dielectric and render.priority_shadows is off: shadow rays stop at it, so "
                       "what it encloses sees the " +
                       light_type_name(*delta) +
                       " light and every other point, spot, box or sun light only by refraction, which cannot reach "
                       "them, and renders dark; set \"priority_shadows\": true in \"render\" to let shadow rays "
                       "through (approximate caustics)");
  }
  return warnings;
}

}  // namespace caligo
