// Volume emission as a light at a path vertex (the proposal is volumes/emission_sampler.h),
// MIS-weighted with the bounce ray that gathers the same emission.
//
// Two strategies estimate the emission reaching a vertex x, and both are directions along which
// the emission of the whole line is integrated (T * e, marched): the bounce direction w drawn
// from the phase function or BSDF with density p_w (the next segment gathers it), and a
// direction towards a point drawn by the emission sampler, with density p_e(w) (its marginal,
// EmissionSampler::direction_pdf), along which a march up to the first surface gathers it.
// Weights are the power heuristic of p_w and p_e, functions of the direction alone. Gathering
// the line rather than weighing the sampled point itself keeps the estimate bounded: a point
// sampled in a volume carries 1 / |x - y|^2, whose variance is infinite for vertices inside the
// emitter (the flame scattering its own light). The bounce's weight is kept in
// PathState::emission_weight from its event until the next one (1 for the camera ray and after
// specular events, which no connection reproduces).
#pragma once

#include <span>

#include "core/rgb.h"
#include "core/vec.h"
#include "integrators/path_context.h"
#include "media/phase.h"

namespace caligo {

// The scattering at a vertex: a phase mixture (`lobes`, `direction` the ray it arrived along) or
// a surface (`surface`, `direction` towards the viewer).
struct EmissionVertex {
  Vec3 p;
  Vec3 direction;
  std::span<const PhaseLobe> lobes;
  const SurfaceInteraction* surface = nullptr;
};

// The emission-guided estimate at path vertex `vertex`, before the throughput at the vertex:
// f(w) * L_e(x, w) * w_e(w) / p_e(w).
RGB emission_direct_light(const PathContext& ctx, const EmissionVertex& v, int vertex);

// The MIS weight of the emission a bounce ray from x along unit `wi`, sampled with solid-angle
// density `scatter_pdf`, will gather (1 when nothing samples emission).
float emission_bounce_weight(const PathContext& ctx, Vec3 x, Vec3 wi, float scatter_pdf);

}  // namespace caligo
