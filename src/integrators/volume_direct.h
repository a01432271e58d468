// Next-event estimation from the medium along one marched ray segment (Kulla & Fajardo
// 2012). One light is chosen in proportion to power; distances along the segment come from
// equiangular sampling about the light (its centre, for area lights; a point on the light
// is then sampled by solid angle from the chosen distance) and from density sampling
// (pdf proportional to sigma_s T from the record). With DistanceSampling::kMis one sample of
// each is taken and weighted by the power heuristic: equiangular wins near the light, density
// where the medium is thick or far from it.
#pragma once

#include "integrators/path_tracer.h"

namespace caligo {

// Radiance scattered towards the ray's origin by the segment's medium, before the path
// throughput. `ray` must have a unit direction.
RGB volume_direct_light(const Scene& scene, const Ray& ray, const TransmittanceRecord& record,
                        const Sampler& sampler, int depth, DistanceSampling strategy, PathScratch& scratch,
                        PathCounters& counters);

// The phase-function mixture stored at a record step.
float mixed_phase_eval(const TransmittanceRecord& record, const MarchStep& step, Vec3 wo, Vec3 wi);

}  // namespace caligo
