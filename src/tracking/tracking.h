// Tracking estimators on the majorant spans of a ray: the alternative to decoupled ray marching
// for the segments where marching pays per voxel but tracking pays per collision, in proportion
// to the majorant's optical depth (bounce and shadow segments deep inside a dense cloud).
//
//   - track_free_flight: the next scattering event by spectral tracking (Kutz et al. 2017,
//     "Spectral and Decomposition Tracking for Rendering Heterogeneous Volumes", sec. 5, with
//     their history-aware probabilities): tentative collisions from one scalar majorant (the
//     largest channel of each span's bound), each one a scattering or a null collision with
//     probabilities proportional to max_c |sigma_{s,c} w_c| and max_c |sigma_{n,c} w_c| (w: the
//     path throughput), weighted so that every channel's estimate stays unbiased. Absorption is
//     never sampled; it is carried by weight (the null and scattering weights both hold the
//     factor (mu - sigma_a) / mu in a grey medium), as the marched path does. Emission is
//     gathered at every tentative collision (w * emission / mu, unbiased for the integral of
//     T * emission), and so are holdouts as extinction (they only matter to camera rays, which
//     are marched). For albedo 1 and grey media the weights are exactly 1: delta tracking.
//   - track_transmittance: shadow rays by residual ratio tracking (Novak et al. 2014, sec. 4)
//     with each span's minimum extinction as the control sigma_c (a grid block's footprint
//     minimum, grids/grid_blocks.h): T = exp(-sigma_c L) times, at each tentative collision of
//     the residual majorant mu_r = mu - sigma_c, (mu_r - (sigma_t - sigma_c)) / mu_r. The
//     control is a lower bound, so every factor is in [0, 1]; a constant block (sigma_c = mu)
//     costs no lookup at all, and elsewhere collisions come at rate mu_r rather than mu. Plain
//     ratio tracking (T *= sigma_n / mu) when `residual` is false, or where the control is 0.
//     Free flight keeps spectral tracking on the full majorant: a control collision still needs
//     a lookup for the event's albedo and phase, so decomposition tracking would save only the
//     lookups of residual null collisions before the first real one (about one per segment in
//     a dense cloud), where a shadow ray saves in proportion to its optical depth.
// Both apply Russian roulette once the running weight falls below kTrackingRouletteThreshold of
// its start (survival with probability weight / threshold, so the survivors carry the threshold):
// unbiased, and it ends the long chains of null collisions that carry almost nothing.
//
// Random numbers come from a Pcg32 the caller seeds from its Sampler (Sampler::stream_key), so
// results are a pure function of the sample, as everywhere in the path tracer.
//
// Both walk the spans collect_spans() builds (raymarch/march.h); t is the ray's parameter, and
// coefficients are scaled by the direction's length as the march does.
#pragma once

#include <cstdint>

#include "core/ray.h"
#include "core/rgb.h"
#include "core/rng.h"
#include "raymarch/march.h"

namespace caligo {

inline constexpr float kTrackingRouletteThreshold = 0.1f;
// A guard against majorants that make a ray endless (optical depth ~10^6): the ray is then opaque.
inline constexpr uint32_t kMaxTrackingCollisions = 1u << 20;

struct TrackedSegment {
  enum class Outcome { kScattered, kPassed, kAbsorbed };
  Outcome outcome = Outcome::kPassed;
  float t = 0.0f;    // the scattering event's ray parameter (kScattered)
  RGB weight{1.0f};  // multiplies the path throughput; its mean is T (passed) or sigma_s T dt (scattered)
  RGB emission;      // radiance emitted towards the ray's origin, relative to the throughput at its start
  RGB sigma_s;       // at the event, per unit t; its phase mixture is in scratch.lobes
  uint32_t collisions = 0;  // tentative collisions (shader evaluations of the span's primitives)
};

// Spectral tracking over the spans collect_spans() left in `scratch`. `throughput`: the path's
// throughput arriving at the segment (the history the probabilities follow); `weight`: the
// walk's running weight so far (1: a new walk); `may_scatter` false makes every collision null
// (the path only takes the segment's transmittance, by ratio tracking). Gathers emission only
// when `gather_emission`.
TrackedSegment track_free_flight(const VolumeScene& volumes, const Ray& ray, RGB throughput, bool may_scatter,
                                 bool gather_emission, MarchScratch& scratch, Pcg32& rng, RGB weight = RGB(1.0f));

// Spectral tracking along the whole segment `ray` whose coarse spans (collect_coarse_spans) are
// in scratch, collecting the fine spans chunk by chunk (see kTrackingChunkDepth).
TrackedSegment track_free_flight_chunked(const VolumeScene& volumes, const Ray& ray, const MarchSettings& settings,
                                         int medium, RGB throughput, bool may_scatter, bool gather_emission,
                                         MarchScratch& scratch, Pcg32& rng);

// A tracked shadow ray collects its spans in chunks of about this majorant optical depth: the
// walk usually ends (roulette, or a weight of 0) within the first few, and a grid's block DDA over
// the rest of the ray would be wasted (it was a quarter of the time on `cloud`).
inline constexpr float kTrackingChunkDepth = 4.0f;

// (Residual) ratio-tracking transmittance along [ray.tmin, ray.tmax], collecting its spans chunk
// by chunk. The chunks' extent comes from a coarse collection (grids as one interval each, no
// block DDA), their lengths from the majorants met so far.
RGB track_transmittance(const VolumeScene& volumes, const Ray& ray, const MarchSettings& settings,
                        MarchScratch& scratch, Pcg32& rng, int medium = -1, bool residual = true);
// The same for a ray whose coarse spans (collect_coarse_spans) are already in scratch.
RGB track_transmittance_chunked(const VolumeScene& volumes, const Ray& ray, const MarchSettings& settings, int medium,
                                MarchScratch& scratch, Pcg32& rng, bool residual = true);
// The same over the spans collect_spans() left in scratch, continuing a walk whose running
// weight is `weight` (1: a new walk).
RGB track_transmittance_collected(const VolumeScene& volumes, const Ray& ray, MarchScratch& scratch, Pcg32& rng,
                                  bool residual = true, RGB weight = RGB(1.0f));

}  // namespace caligo
