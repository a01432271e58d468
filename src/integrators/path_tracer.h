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
#include "raymarch/march.h"
#include "raymarch/transmittance_record.h"
#include "scene/scene.h"

namespace caligo {

// How next-event estimation in media picks the distance along a ray segment.
enum class DistanceSampling {
  kDensity,      // pdf proportional to sigma_s T
  kEquiangular,  // pdf cancelling the light's inverse-square falloff (density for lights at infinity)
  kMis,          // one of the two at random, weighted by the balance heuristic (one-sample MIS);
                 // equiangular's share follows the segment's optical depth (volume_direct.h)
  kMisFixed,     // the same with equiangular's share fixed at 3/4 (the former default)
};

struct PathSettings {
  // Events of a path: each surface bounce, and each run of consecutive scattering events in
  // media, counts one against max_depth (1 = direct lighting only, of surfaces and media);
  // max_volume_bounces bounds the scattering events in media.
  int max_depth = 8;
  int max_volume_bounces = 128;
  int russian_roulette_depth = 3;  // roulette starts after this many events
  int max_null_crossings = 256;    // guards against endless chains of null surfaces
  DistanceSampling distance_sampling = DistanceSampling::kMis;
  // Volume next-event estimation runs with probability min(1, scale * P(scatter in segment)).
  float volume_nee_scale = 2.0f;
  // How next-event estimation picks a light (lights/light_sampler.h; Scene::light_sampler). The
  // tree is the default: ~90x less MSE than power at equal time on many-lamps, and the same
  // choice (bit for bit) as power in scenes with one light.
  LightSamplerKind light_sampler = LightSamplerKind::kTree;
  // true: the path scatters with probability P(scatter in segment) and otherwise passes with
  // the segment's exact transmittance (absorption by weight). false: analog free-flight
  // sampling, where a collision that absorbs ends the path (kept for comparisons).
  bool absorption_by_weight = true;
  // Deferred next-event estimation (the seed's "optimizations for multiple scattering"): 0 (the
  // default) connects each medium segment to a light as the path goes; K > 0 builds the whole
  // path first, then connects K of its scattering vertices, chosen with probability
  // proportional to their throughput (~ sigma_s T along the path) and weighted by the inverse.
  // Light hits from medium vertices then count zero (the connections alone are unbiased).
  // See docs/techniques.md for when it pays.
  int deferred_nee = 0;
};

// What one camera path contributes to the film and its AOVs.
struct PathSample {
  RGB radiance;
  float alpha = 0.0f;       // coverage: 1 on a visible surface, 1 - T through media
  float hit_t = kInfinity;  // ray parameter of the first visible surface
  Vec3 normal;              // its shading normal (zero when nothing was hit)
  RGB albedo;               // its material's reflectance
};

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
