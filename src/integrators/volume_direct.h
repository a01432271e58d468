// Next-event estimation from the medium along one marched ray segment (Kulla & Fajardo
// 2012). One light is chosen for the segment by the scene's light sampler (segment form; the
// light tree by default); distances along the segment come from
// equiangular sampling about the light (its centre, for area lights; a point on the light
// is then sampled by solid angle from the chosen distance) and from density sampling
// (pdf proportional to sigma_s T from the record). With DistanceSampling::kMis one of the two
// is chosen at random (equiangular with the adaptive share s = 0.95 - 0.2 min(tau, 1); 3/4 with
// kMisFixed) and the sample is divided by the
// mixture density:
// one-sample MIS with the balance heuristic, which Veach (1997, 9.2.4) shows is the best
// weighting in the one-sample model. Equiangular wins near the light, density where the
// medium is thick or far from it; the cost is one light connection, as for either alone.
#pragma once

#include <span>

#include "integrators/path_context.h"

namespace caligo {

// Radiance scattered towards the ray's origin by the segment's medium, before the path
// throughput. `ray` must have a unit direction. ctx.lights chooses one light for the whole
// segment (LightSampler::sample_segment of light_choice_segment()). `vertex` is the path vertex
// whose sample dimensions it draws; `secondary` says whether its shadow rays follow
// PathSettings::secondary (false for the camera segment: marched).
RGB volume_direct_light(const PathContext& ctx, const Ray& ray, const TransmittanceRecord& record, int vertex,
                        bool secondary);

// Next-event estimation at one scattering point x of a tracked segment (no record): one light by
// the light sampler's point form, one point on it, the phase mixture `lobes` towards it, the
// shadow ray's transmittance, weighted by the power heuristic against phase sampling. Per unit
// throughput at x (after the collision's weight, before the phase sample); `direction` is the
// ray's, so the radiance goes back along it; `segment_t` is x's ray parameter (nested media:
// the false crossings before it apply to the shadow ray's stack).
RGB point_volume_direct_light(const PathContext& ctx, Vec3 x, Vec3 direction, std::span<const PhaseLobe> lobes,
                              int vertex, float segment_t);

// The segment volume next-event estimation chooses its light for: the ray over the record's
// extent. A phase-sampled hit from a vertex on that segment weights its MIS with the same
// segment's pmf, so the two strategies' weights sum to one at every point of it.
inline Ray light_choice_segment(const Ray& ray, const TransmittanceRecord& record) {
  return {ray.origin, ray.direction, record.t_begin(), record.t_end()};
}

// The phase-function mixture of a record step or a tracked event, per colour channel.
RGB mixed_phase_eval(std::span<const PhaseLobe> lobes, Vec3 wo, Vec3 wi);
// The density with which sample_mixed_phase() picks wi: lobes chosen by their average weight.
float mixed_phase_pdf(std::span<const PhaseLobe> lobes, Vec3 wo, Vec3 wi);

struct MixedPhaseSample {
  Vec3 wi;
  RGB weight;  // mixed_phase_eval / mixed_phase_pdf
  float pdf;
};
MixedPhaseSample sample_mixed_phase(std::span<const PhaseLobe> lobes, Vec3 wo, float u_lobe, Vec2 u);

}  // namespace caligo
