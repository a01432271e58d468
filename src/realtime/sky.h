// The sky of a real-time frame: what the camera sees where no surface is, as the path tracer's
// camera ray that leaves the scene sees it (the visible environment lights' radiance along the
// ray, times the media's transmittance to where it leaves them). The fog's own in-scattering in
// front of the sky is the volumetric passes'. Without a visible environment the sky is black.
#pragma once

#include "realtime/plane.h"
#include "realtime/scene_buffers.h"
#include "realtime/view.h"

namespace caligo {

class Scene;

// Writes the sky pixels of `out` (depth >= kSkyDepth); the others are left as they are.
void shade_sky(const GBuffer& gbuffer, const View& camera, const Scene& scene, ColorPlanes& out);

}  // namespace caligo
