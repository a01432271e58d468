// One light as a real-time frame sees it: the light at the frame's time, its real-time
// options, and its shadow map (null when it casts none or is not shadowed in real time).
#pragma once

#include "lights/light.h"
#include "scene/scene_desc.h"

namespace caligo {

struct ShadowMap;

struct FrameLight {
  Light light;
  LightOptions options;
  const ShadowMap* shadow = nullptr;
};

}  // namespace caligo
