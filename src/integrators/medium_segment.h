// Phases 2 and 3 of the seed for one path segment in media: marched (decoupled ray marching
// into a TransmittanceRecord, light connection along it, the fate sampled from it) or, after the
// first bounce, tracked (tracking/tracking.h) as PathSettings::secondary says; then the phase
// sample that continues the path. One of path_tracer.cpp's named events.
#pragma once

#include "core/ray.h"
#include "integrators/path_context.h"
#include "integrators/path_state.h"

namespace caligo {

// kLayer: the path meets a partly transparent surface in front of the segment's end (one of
// scratch.layer_hits, which the march recorded as layers of the TransmittanceRecord).
enum class SegmentOutcome { kScattered, kPassed, kAbsorbed, kLayer };

struct SegmentEvent {
  float t = kInfinity;  // the event's distance along the segment's ray
  int layer = -1;       // kLayer: the index in scratch.layer_hits
};

// The medium in front of the next surface (at t_surface, or infinity), and the partly transparent
// surfaces in scratch.layer_hits before it. `medium`: the scene medium the stack puts the segment
// in (-1: none). On kScattered, `ray` is the new ray; on kScattered and kLayer *event says where;
// on kPassed and kLayer the throughput carries what the path met on the way.
SegmentOutcome medium_segment(const PathContext& ctx, PathState& state, Ray& ray, float t_surface, int medium,
                              PathSample& out, SegmentEvent* event);

// The position of heterogeneous march steps for this path vertex (constant when no primitive is
// heterogeneous, which saves a sample).
float march_jitter(const Scene& scene, const Sampler& sampler, int depth);

}  // namespace caligo
