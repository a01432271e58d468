// Decoupled ray marching (the seed's "Ray Marching"; Kulla & Fajardo 2012): the volume
// primitives along one ray segment are split into spans, their shaders run front to back
// with a step size per primitive, and every step is stored in a TransmittanceRecord. No
// lighting happens here: one record serves every light sample taken along the segment.
//
// Step rules: a span whose intervals are all homogeneous (homogeneous primitives, constant
// grid blocks) is one step; otherwise the span is cut into equal steps no longer than the
// smallest step size among its heterogeneous primitives (about one voxel for grids), each
// shaded at a jittered position (the same jitter for the whole ray, so the estimate stays
// smooth along it). Empty grid blocks yield no interval, so they cost nothing. Marching stops once every channel's
// transmittance is below the opacity threshold: what lies behind contributes at most
// that fraction and is dropped (a documented bias).
//
// t is in units of the ray direction's length; coefficients in the record are per unit t.
#pragma once

#include <span>
#include <vector>

#include "core/ray.h"
#include "settings/march_settings.h"
#include "raymarch/spans.h"
#include "raymarch/transmittance_record.h"
#include "volumes/volume_scene.h"

namespace caligo {

// Per-thread buffers, reused from ray to ray.
struct MarchScratch {
  VolumeContext volume;  // intervals and grid accessors
  SpanScratch span_scratch;
  std::vector<Span> spans;
  std::vector<uint32_t> span_primitives;
  std::vector<PhaseLobe> lobes;
  uint64_t steps = 0;               // statistics: steps marched (records and shadow rays)
  uint64_t shader_evaluations = 0;  // statistics: volume shader calls
};

// Coefficients summed over the primitives covering a span at one point, per unit t (`scale`
// is the ray direction's length).
struct StepCoefficients {
  RGB sigma_t, sigma_s, emission;
  float holdout = 0.0f;
};
// `lobes` (when given) receives the phase mixture there, each lobe weighted by its share of
// sigma_s per channel.
StepCoefficients shade_span(const VolumeScene& volumes, std::span<const uint32_t> primitives, Vec3 p, float scale,
                            VolumeContext& context, std::vector<PhaseLobe>* lobes);

// Medium tracking for one segment: the majorant spans of [ray.tmin, ray.tmax] into scratch.spans
// and scratch.span_primitives (what march, march_transmittance and the tracking estimators of
// tracking/ walk). True when there is at least one span.
bool collect_spans(const VolumeScene& volumes, const Ray& ray, const MarchSettings& settings, MarchScratch& scratch,
                   int medium = -1);
// The same without the block DDA: each grid is one interval over its stretch with its global
// majorant (cheap: the BVH query and a box clip). Homogeneous primitives give the same spans
// either way, so a caller that finds them all homogeneous has the spans it needs; tracking
// reads the extent and bound of a ray from them and collects the fine spans chunk by chunk.
bool collect_coarse_spans(const VolumeScene& volumes, const Ray& ray, const MarchSettings& settings,
                          MarchScratch& scratch, int medium = -1);
// True when every collected span is homogeneous (each is one closed-form step).
bool collected_spans_homogeneous(const MarchScratch& scratch);
// True when a primitive of the collected spans emits (a constant emission, blackbody or flame):
// marching integrates its emission exactly per step, where tracking would gather it at
// tentative collisions of the extinction's majorant (noisy where a flame is hot but thin).
bool collected_spans_emissive(const VolumeScene& volumes, const MarchScratch& scratch);

// Marches the spans collect_spans() left in scratch into `out` (the second half of march()).
void march_collected(const VolumeScene& volumes, const Ray& ray, float jitter, const MarchSettings& settings,
                     MarchScratch& scratch, TransmittanceRecord& out);

// march_transmittance over the spans collect_spans() left in scratch.
RGB march_transmittance_collected(const VolumeScene& volumes, const Ray& ray, float jitter,
                                  const MarchSettings& settings, MarchScratch& scratch);

// Marches [ray.tmin, ray.tmax] (tmax: the nearest opaque surface, or infinity) into `out`.
// `medium`: the scene medium the ray travels in (media/medium_stack.h; -1: none), which adds to
// the volume primitives over the whole segment (smoke under water).
void march(const VolumeScene& volumes, const Ray& ray, float jitter, const MarchSettings& settings,
           MarchScratch& scratch, TransmittanceRecord& out, int medium = -1);

// Transmittance along [ray.tmin, ray.tmax] with the same step rules, without a record (shadow rays).
RGB march_transmittance(const VolumeScene& volumes, const Ray& ray, float jitter,
                        const MarchSettings& settings, MarchScratch& scratch, int medium = -1);

// The emission a ray gathers, the integral of T * emission over [ray.tmin, ray.tmax], with the
// march's step rules and without a record (or the phase lobes a record's event would need).
RGB march_emission(const VolumeScene& volumes, const Ray& ray, float jitter, const MarchSettings& settings,
                   MarchScratch& scratch);

// The step size used for a primitive: its own, or the automatic one (a voxel for grids, a
// fraction of the bounds otherwise) times its step_scale; infinity if homogeneous.
float primitive_step_size(const VolumePrimitive& primitive, const MarchSettings& settings);

}  // namespace caligo
