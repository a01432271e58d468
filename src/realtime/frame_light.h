// One light as a real-time frame sees it. The real-time passes shade a closed set of their own,
// ShadedLight: point, spot, box and directional lights. Area lights and the environment are
// shaded through stand-ins of those types (realtime/light_stand_ins.h). shaded_lights() is the
// one place in realtime/ and hybrid/ that visits the full `Light` variant: it passes the types
// ShadedLight holds, turns the others into their stand-ins, and leaves a type it does not know
// to the path tracer (the command warns). A new type needs nothing here; one the passes shade
// joins ShadedLight, after which the compiler names every pass that must handle it.
#pragma once

#include <optional>
#include <variant>
#include <vector>

#include "lights/light.h"
#include "scene/scene_desc.h"

namespace caligo {

struct ShadowMap;
class LightDepthVolume;

using ShadedLight = std::variant<PointLight, SpotLight, BoxLight, DirectionalLight>;

// One of the lights that shade a scene light, and the factor on its in-scattering (an
// environment sun's 1 / |m|: realtime/light_stand_ins.h).
struct ShadedPart {
  ShadedLight light;
  float volumetric_scale = 1.0f;
};
// The light as the real-time passes shade it: itself, its stand-in, `environment_lights` suns
// for the environment (fewer for a map with few bright cells), or nothing.
std::vector<ShadedPart> shaded_lights(const Light& light, int environment_lights);
// The one light that shades `light`, or nullopt (left out, or an environment: several).
std::optional<ShadedLight> shaded_light(const Light& light);
// The lights the passes leave to the path tracer.
inline bool is_shaded(const Light& light) { return !shaded_lights(light, 1).empty(); }

// What a shadow map depends on: the light's type, placement and shape, as numbers to compare
// frame to frame (a light whose key is unchanged keeps last frame's map).
std::vector<float> placement_key(const ShadedLight& light);

struct FrameLight {
  ShadedLight light;  // at the frame's time
  LightOptions options;
  const ShadowMap* shadow = nullptr;  // null when it casts none or is not shadowed in real time
  // Stable from frame to frame, the key of per-light caches (shadow maps, froxel history):
  // the scene's index of the light, or past the scene's lights for an environment's further suns.
  size_t index = 0;
  size_t scene_light = 0;  // the scene light it shades (per-light timings and reports)
  int skip_emitter = -1;   // the scene light whose geometry its shadow map leaves out (a stand-in's own)
  // What surfaces look up when it differs from `shadow`: a sun's cascades (the march keeps the
  // one face over the scene: realtime/directional_faces.h).
  const ShadowMap* surface_shadow = nullptr;
  const ShadowMap* surface_map() const { return surface_shadow ? surface_shadow : shadow; }
  // A directional light's transmittance through the grid volumes, tabulated (null: integrated
  // at every step; realtime/light_depth_volume.h).
  const LightDepthVolume* media_depth = nullptr;
};

// Every light of the scene the passes shade, posed (`posed`, as desc.lights_at gives them),
// with its options, cache index and emitter; shadows are attached later.
std::vector<FrameLight> frame_lights(const SceneDesc& desc, const std::vector<Light>& posed, int environment_lights);

}  // namespace caligo
