// One light as a real-time frame sees it. The real-time passes shade a closed set of their own,
// ShadedLight: point, spot, box and directional lights; area and environment lights are left
// to the path tracer. shaded_light() is the one place in realtime/ and hybrid/ that visits the
// full `Light` variant, and it passes the types ShadedLight holds: a new light type the passes
// do not shade needs nothing here, and one they shade joins ShadedLight, after which the
// compiler names every pass that must handle it.
#pragma once

#include <optional>
#include <variant>
#include <vector>

#include "lights/light.h"
#include "scene/scene_desc.h"

namespace caligo {

struct ShadowMap;

using ShadedLight = std::variant<PointLight, SpotLight, BoxLight, DirectionalLight>;

// The light as the real-time passes shade it; nullopt for the lights they leave out.
std::optional<ShadedLight> shaded_light(const Light& light);

// What a shadow map depends on: the light's type, placement and shape, as numbers to compare
// frame to frame (a light whose key is unchanged keeps last frame's map).
std::vector<float> placement_key(const ShadedLight& light);

struct FrameLight {
  ShadedLight light;  // at the frame's time
  LightOptions options;
  const ShadowMap* shadow = nullptr;  // null when it casts none or is not shadowed in real time
  size_t index = 0;                   // in the scene's lights
};

}  // namespace caligo
