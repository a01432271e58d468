// Phases 2 and 3 of the seed for one path segment in media: marched (decoupled ray marching
// into a TransmittanceRecord, light connection along it, the fate sampled from it) or, after the
// first bounce, tracked (tracking/tracking.h) as PathSettings::secondary says; then the phase
// sample that continues the path. One of path_tracer.cpp's named events.
#pragma once

#include "core/ray.h"
#include "integrators/path_context.h"
#include "integrators/path_state.h"

namespace caligo {

enum class SegmentOutcome { kScattered, kPassed, kAbsorbed };

// The medium in front of the next surface (at t_surface, or infinity). `medium`: the scene medium
// the stack puts the segment in (-1: none). On kScattered, `ray` is the new ray and *event_t the
// event's distance along the old one; on kPassed the throughput carries the transmittance.
SegmentOutcome medium_segment(const PathContext& ctx, PathState& state, Ray& ray, float t_surface, int medium,
                              PathSample& out, float* event_t);

// The position of heterogeneous march steps for this path vertex (constant when no primitive is
// heterogeneous, which saves a sample).
float march_jitter(const Scene& scene, const Sampler& sampler, int depth);

}  // namespace caligo
