// Simple surface lighting of a real-time frame, so that it looks like a game frame:
// diffuse reflectance / pi x irradiance from each point, spot, box and directional light
// (the same light models as the path tracer, through lights/light_profile.h), times the
// light's shadow-map visibility, times the transmittance of the media between the surface
// and the light, plus the material's emission; all times the camera ray's transmittance.
// For diffuse surfaces lit by delta lights this is what the path tracer renders with
// --max-depth 1 (sphere, quad, triangle and environment lights are not shaded here; a sun
// with an angular radius is shaded as a delta direction).
//
// Lights are culled per 16 x 16 pixel tile against the tile's world-space bounds (range
// spheres and box-light volumes), as a Forward+ renderer does. Sky pixels are black. The
// SIMD path evaluates point, spot, box and directional lights 8 pixels at a time; lights
// with a gobo image or an IES profile, cube-map lookups and media transmittance fall back
// to the scalar functions lane by lane.
#pragma once

#include <span>

#include "realtime/frame_light.h"
#include "realtime/plane.h"
#include "realtime/scene_buffers.h"
#include "realtime/view.h"

namespace caligo {

class Scene;

// `simd = false` runs the scalar reference path (tests compare the two within 1e-4).
ColorPlanes shade_surfaces(const GBuffer& gbuffer, const View& camera, const Scene& scene,
                           std::span<const FrameLight> lights, bool simd = true);

}  // namespace caligo
