// The volumetric path tracer: the three phases of the seed (Kulla, "Volume Rendering
// Techniques at Imageworks") for every segment of a path:
//   1. medium tracking: the nearest surface that is seen (null surfaces, and priority surfaces
//      the medium stack calls false hits, are crossed without restarting anything), then the
//      volume primitives' intervals up to it, plus the medium the stack puts the ray in
//      (media/medium_stack.h: nested dielectrics, camera in a medium, clipping volumes);
//   2. decoupled ray marching of those intervals into a TransmittanceRecord, gathering
//      emission on the way;
//   3. importance sampling: next-event estimation in the medium (equiangular and density
//      sampling combined by MIS, see volume_direct.h), free-flight sampling of the next
//      scattering distance from the same record, phase sampling, Russian roulette.
// Surfaces use next-event estimation and BSDF sampling combined by the power heuristic.
//
// One call traces one camera path; the result is a pure function of the scene, the camera
// ray and the Sampler, so images do not depend on thread count or scheduling.
#pragma once

#include <cstdint>

#include "core/rgb.h"
#include "core/sampler.h"
#include "integrators/path_context.h"
#include "integrators/path_sample.h"
#include "integrators/path_settings.h"
#include "scene/scene.h"

namespace caligo {

// The position of heterogeneous march steps for this path vertex (constant when no
// primitive is heterogeneous, which saves a sample).
float march_jitter(const Scene& scene, const Sampler& sampler, int depth);

PathSample trace_path(const Scene& scene, Ray ray, const Sampler& sampler, const PathSettings& settings,
                      PathCounters& counters, PathScratch& scratch);

}  // namespace caligo
