// priority_shadow_warnings: a lit object inside priority glass is not silently black.
#include <gtest/gtest.h>

#include "scene/scene_parser.h"
#include "scene/scene_warnings.h"

namespace caligo {
namespace {

SceneDesc glass_with(const std::string& render, const std::string& light) {
  return parse_scene_text(R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]}, "render": )" + render +
                              R"(, "materials": {"glass": {"type": "dielectric", "ior": 1.5, "priority": "normal",
                                  "interior": "ink"}, "white": {"type": "diffuse", "reflectance": 0.8}},
                                  "media": {"ink": {"sigma_s": 1, "sigma_a": 0.1}},
                                  "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "glass"},
                                             {"type": "sphere", "center": [0, 0, 0], "radius": 0.2, "material": "white"},
                                             {"type": "sphere", "center": [3, 0, 0], "radius": 1, "material": "glass"}],
                                  "lights": [)" + light + "]}",
                          "glass.json", "");
}

constexpr const char* kPoint = R"({"type": "point", "position": [0, 3, 0], "intensity": 10})";

TEST(SceneWarnings, APointLightOutsidePriorityGlassIsNamedOnce) {
  const auto w = priority_shadow_warnings(glass_with("{}", kPoint));
  ASSERT_EQ(w.size(), 1u);  // two shapes, one material
  EXPECT_NE(w[0].find("material \"glass\" (glass.json: /shapes/0)"), std::string::npos) << w[0];
  EXPECT_NE(w[0].find("priority_shadows"), std::string::npos) << w[0];
  EXPECT_NE(w[0].find("point light"), std::string::npos) << w[0];
}

TEST(SceneWarnings, NoneWithPriorityShadowsOrWithoutDeltaLights) {
  EXPECT_TRUE(priority_shadow_warnings(glass_with(R"({"priority_shadows": true})", kPoint)).empty());
  // An area light is found by refracted paths (noisy, not black).
  EXPECT_TRUE(priority_shadow_warnings(
                  glass_with("{}", R"({"type": "sphere", "center": [0, 3, 0], "radius": 0.3, "radiance": 5})"))
                  .empty());
}

}  // namespace
}  // namespace caligo
