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
// After the first bounce, segments through heterogeneous media may be tracked instead of marched
// (PathSettings::secondary: spectral tracking, ratio-tracked shadow rays; medium_segment.h).
// The loop is a sequence of named events over one PathContext: segment end, the medium segment,
// escape, surface hit (path_tracer.cpp), and scattering in a medium (medium_segment.cpp).
// Surfaces use next-event estimation and BSDF sampling combined by the power heuristic.
//
// One call traces one camera path; the result is a pure function of the scene, the camera
// ray and the Sampler, so images do not depend on thread count or scheduling.
#pragma once

#include <cstdint>

#include "core/rgb.h"
#include "core/sampler.h"
#include "integrators/medium_segment.h"
#include "integrators/path_context.h"
#include "integrators/path_sample.h"
#include "settings/path_settings.h"
#include "scene/scene.h"

namespace caligo {

// Path guiding for one sample: the field it samples from (null: none; settings.guiding says
// where) and whether it trains the field (render/render.cpp follows guiding/guiding_schedule.h).
struct PathGuiding {
  const GuidingField* field = nullptr;
  bool train = false;
};

PathSample trace_path(const Scene& scene, Ray ray, const Sampler& sampler, const PathSettings& settings,
                      PathCounters& counters, PathScratch& scratch, PathGuiding guiding = {});

}  // namespace caligo
