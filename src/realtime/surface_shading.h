// Simple surface lighting of a real-time frame, so that it looks like a game frame:
// diffuse reflectance / pi x irradiance from each point, spot, box and directional light
// (the same light models as the path tracer, through lights/light_profile.h), times the
// light's shadow-map visibility, times the transmittance of the media between the surface
// and the light, plus the material's emission; all times the camera ray's transmittance.
// For diffuse surfaces lit by delta lights this is what the path tracer renders with
// --max-depth 1 (area lights and the environment arrive as their delta stand-ins,
// realtime/light_stand_ins.h; a sun with an angular radius is shaded as a delta direction).
//
// Lights are culled per 64 x 4 pixel tile against the tile's world-space bounds (range
// spheres, spot cones, box-light volumes), as a Forward+ renderer does; tiles are wide
// because their rows are what the G-buffer loads stream through. Sky pixels are black here;
// realtime/sky.h draws the visible environment in them.
// The SIMD path (surface_shading_simd.cpp) evaluates every delta light 8 pixels at a time,
// gobos and media transmittance included; only IES profiles and cube-map lookups that
// straddle faces call the scalar functions lane by lane.
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
// The same into `out`, reusing its storage when the size matches (a new 1080p frame's three
// zeroed planes cost ~10 ms of page faults); every pixel is overwritten.
void shade_surfaces(const GBuffer& gbuffer, const View& camera, const Scene& scene,
                    std::span<const FrameLight> lights, ColorPlanes& out, bool simd = true);

}  // namespace caligo
