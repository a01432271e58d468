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
#include "integrators/path_sample.h"
#include "integrators/path_settings.h"
#include "raymarch/march.h"
#include "raymarch/transmittance_record.h"
#include "scene/scene.h"

namespace caligo {


struct PathCounters {
  uint64_t rays = 0;                // every Embree query: camera, bounce and shadow rays
  uint64_t camera_march_steps = 0;  // steps stored in camera rays' records
};

// A crossing of a priority surface that the stack rules made a false hit (nothing seen), at
// ray parameter t of the current segment; applied to the path's stack once the path is known
// to have got past it.
struct PendingCrossing {
  float t;
  MediumEntry entry;
};

// Per-thread buffers, reused from path to path (no allocation per ray once grown).
struct PathScratch {
  MarchSettings march_settings;
  MarchScratch march;
  TransmittanceRecord record;
  // Nested dielectrics (scenes with priority surfaces only): the path's medium stack, the
  // false hits of the current segment, and a working copy for probes and shadow rays.
  MediumStack stack;
  std::vector<PendingCrossing> pending;
  MediumStack work;
  std::vector<SurfaceHit> shadow_hits;
  // Deferred next-event estimation (PathSettings::deferred_nee): the path's scattering vertices
  // in media, their phase lobes and (with nested media) their medium stacks.
  struct DeferredVertex {
    Vec3 x, wo;  // the vertex and the direction the path arrived along
    RGB beta;    // throughput at the vertex, before the phase sample
    LightKind kind;  // the light layer a connection from it feeds
    uint32_t first_lobe, lobe_count;
  };
  std::vector<DeferredVertex> deferred;
  std::vector<PhaseLobe> deferred_lobes;
  std::vector<MediumStack> deferred_stacks;
};

// The position of heterogeneous march steps for this path vertex (constant when no
// primitive is heterogeneous, which saves a sample).
float march_jitter(const Scene& scene, const Sampler& sampler, int depth);

PathSample trace_path(const Scene& scene, Ray ray, const Sampler& sampler, const PathSettings& settings,
                      PathCounters& counters, PathScratch& scratch);

}  // namespace caligo
