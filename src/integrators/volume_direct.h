// Next-event estimation from the medium along one marched ray segment (Kulla & Fajardo
// 2012). One light is chosen in proportion to power; distances along the segment come from
// equiangular sampling about the light (its centre, for area lights; a point on the light
// is then sampled by solid angle from the chosen distance) and from density sampling
// (pdf proportional to sigma_s T from the record). With DistanceSampling::kMis one of the two
// is chosen at random (equiangular with probability 3/4) and the sample is divided by the
// mixture density:
// one-sample MIS with the balance heuristic, which Veach (1997, 9.2.4) shows is the best
// weighting in the one-sample model. Equiangular wins near the light, density where the
// medium is thick or far from it; the cost is one light connection, as for either alone.
#pragma once

#include "integrators/path_tracer.h"

namespace caligo {

// Radiance scattered towards the ray's origin by the segment's medium, before the path
// throughput. `ray` must have a unit direction. `lights` chooses one light for the whole
// segment (LightSampler::sample_segment of light_choice_segment()).
RGB volume_direct_light(const Scene& scene, const LightSampler& lights, const Ray& ray,
                        const TransmittanceRecord& record, const Sampler& sampler, int depth,
                        DistanceSampling strategy, PathScratch& scratch, PathCounters& counters);

// The segment volume next-event estimation chooses its light for: the ray over the record's
// extent. A phase-sampled hit from a vertex on that segment weights its MIS with the same
// segment's pmf, so the two strategies' weights sum to one at every point of it.
inline Ray light_choice_segment(const Ray& ray, const TransmittanceRecord& record) {
  return {ray.origin, ray.direction, record.t_begin(), record.t_end()};
}

// The phase-function mixture stored at a record step, per colour channel.
RGB mixed_phase_eval(const TransmittanceRecord& record, const MarchStep& step, Vec3 wo, Vec3 wi);
// The density with which sample_mixed_phase() picks wi: lobes chosen by their average weight.
float mixed_phase_pdf(const TransmittanceRecord& record, const MarchStep& step, Vec3 wo, Vec3 wi);

struct MixedPhaseSample {
  Vec3 wi;
  RGB weight;  // mixed_phase_eval / mixed_phase_pdf
  float pdf;
};
MixedPhaseSample sample_mixed_phase(const TransmittanceRecord& record, const MarchStep& step, Vec3 wo,
                                    float u_lobe, Vec2 u);

}  // namespace caligo
