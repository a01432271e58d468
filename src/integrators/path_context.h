// What every stage of one camera path reads and writes besides the path's own state: the scene,
// the sample, the settings, the per-thread buffers and the statistics. The path tracer's named
// events (path_tracer.cpp), its light connections (volume_direct.h) and visibility take one of
// these instead of the same five arguments each.
#pragma once

#include <cstdint>
#include <vector>

#include "core/sampler.h"
#include "guiding/guiding_field.h"
#include "integrators/guided_vertex.h"
#include "integrators/path_sample.h"
#include "settings/path_settings.h"
#include "media/medium_stack.h"
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
  // Partly transparent surfaces in front of the current segment's end, in order, and the layers
  // the march records for them (one per hit, same order); line_layers: an emission line's.
  std::vector<SurfaceHit> layer_hits;
  std::vector<SurfaceLayer> layers;
  std::vector<SurfaceHit> line_layers;
  // Deferred next-event estimation (PathSettings::deferred_nee): the path's marched segments in
  // media (their ray and a copy of their record) and scattering vertices of tracked segments,
  // each with its throughput, its phase lobes (vertices) and, with nested media, its medium stack
  // and the segment's false crossings.
  struct DeferredVertex {
    Vec3 x, wo;  // the vertex and the direction the path arrived along (vertices)
    RGB beta;    // throughput at the vertex before the phase sample, or at the segment's start
    LightKind kind;  // the light layer a connection from it feeds
    uint32_t first_lobe, lobe_count;
    int segment = -1;     // >= 0: the marched segment deferred_segments[segment] (x, wo, lobes unused)
    float weight = 0.0f;  // its share of the connections: beta x the segment's scatter probability
  };
  struct DeferredSegment {
    Ray ray;
    bool secondary;  // its shadow rays follow PathSettings::secondary
  };
  std::vector<DeferredVertex> deferred;
  std::vector<PhaseLobe> deferred_lobes;
  std::vector<DeferredSegment> deferred_segments;
  std::vector<TransmittanceRecord> deferred_records;  // per segment; reused from path to path
  std::vector<std::vector<PendingCrossing>> deferred_pending;  // per entry (nested media)
  std::vector<MediumStack> deferred_stacks;
  // Path guiding's training: the path's guided vertices, whose incident radiance is what the
  // path adds to the image after them (integrators/guided_direction.h).
  std::vector<GuidedVertex> guided;
  // The product, over the path's guided vertices so far, of native density / mixture density at
  // the direction taken: how far guiding has raised the throughput above what native sampling
  // would carry (guided_direction.h's kMaxGuidedGrowth bounds it).
  float guided_growth = 1.0f;
};

struct PathContext {
  const Scene& scene;
  const Sampler& sampler;
  const PathSettings& settings;
  PathScratch& scratch;
  PathCounters& counters;
  const LightSampler& lights;  // Scene::light_sampler(settings.light_sampler)
  bool nested;                 // the scene has priority surfaces (medium stacks)
  bool has_volumes;            // volume primitives or surface-bounded media
  // Volume emission as a light (integrators/emission_direct.h); null when nothing emits in a
  // grid or PathSettings::sample_emission is off.
  const EmissionSampler* emission = nullptr;
  // Path guiding (integrators/guided_direction.h): the field to sample from (null: none), where
  // it applies, and whether this sample trains it.
  const GuidingField* guide = nullptr;
  bool guide_surfaces = false, guide_volumes = false, train = false;
};

}  // namespace caligo
