// Path guiding at a path vertex (guiding/guiding_field.h holds the learnt field): the next
// direction by one-sample MIS of the guided density and the BSDF's or phase function's -- the
// direction comes from the guide with probability alpha (the share its leaf learnt for surface
// or medium vertices: DirectionalTree::fraction) and
// from the BSDF or phase function otherwise, and is weighted by f / (alpha p_guide + (1 - alpha)
// p_native), the balance heuristic of the two for one sample (Mueller et al. 2017). Where the
// field knows nothing yet, the native sampling runs alone, drawing what it always draws. The
// product with the BSDF or phase function is not learnt: the mixture keeps both supports, so
// the estimate stays unbiased whatever the field holds.
// Training: each guided vertex is remembered with the throughput after it; once the path ends,
// what it added to the image after the vertex, over that throughput, is the radiance that came
// back along the direction, which goes into the field over the direction's pdf.
#pragma once

#include <optional>
#include <span>

#include "integrators/path_context.h"
#include "integrators/path_sample.h"
#include "integrators/volume_direct.h"
#include "materials/bsdf.h"

namespace caligo {

// The directional distribution a vertex at x samples from: null when guiding is off there or the
// field knows nothing at x.
const DirectionalTree* surface_guide(const PathContext& ctx, Vec3 x, const Bsdf& bsdf);
const DirectionalTree* volume_guide(const PathContext& ctx, Vec3 x);
// Whether this path's distances in media are guided (integrators/guided_distance.h): volume
// guiding on, a field with at least one iteration, and the path's growth within its bound.
bool volume_guides_distances(const PathContext& ctx);

// After a vertex's guided sample and every MIS weight at the vertex: the path's growth
// (PathScratch::guided_growth) by the sample's native over mixture density.
void note_guided_sample(const PathContext& ctx, float pdf_native, float pdf);

// The mixtures. `vertex` is the sampler's vertex index (PathState::vertex()).
std::optional<BsdfSample> guided_bsdf_sample(const PathContext& ctx, const DirectionalTree& guide, const Bsdf& bsdf,
                                             Vec3 n, Vec3 wo, int vertex);
MixedPhaseSample guided_phase_sample(const PathContext& ctx, const DirectionalTree& guide,
                                     std::span<const PhaseLobe> lobes, Vec3 wo, int vertex);

// The density with which a vertex at x samples wi: the mixture where a guide is at x, the
// phase function's or BSDF's alone elsewhere. Every MIS weight against that sampling (light and
// emission connections at the vertex) must use this, or the weights no longer sum to one.
float phase_sampling_pdf(const PathContext& ctx, Vec3 x, std::span<const PhaseLobe> lobes, Vec3 wo, Vec3 wi);
float bsdf_sampling_pdf(const PathContext& ctx, Vec3 x, const Bsdf& bsdf, Vec3 n, Vec3 wo, Vec3 wi);

// Training. Whether a vertex of this kind trains (guiding on there and this sample in a training
// iteration); remembering one; and, at the end of the path, handing its vertices to the field.
bool trains_surface(const PathContext& ctx, const Bsdf& bsdf);
bool trains_volume(const PathContext& ctx);
// `weight` and `pdf`: of the sample taken (f = weight * pdf); `pdf_native`: the BSDF's or phase
// function's density at its direction.
void remember_guided_vertex(const PathContext& ctx, Vec3 x, bool surface, Vec3 wi, RGB weight, float pdf,
                            float pdf_native, RGB throughput, const PathSample& out);
void train_guide(const PathContext& ctx, const PathSample& out);

}  // namespace caligo
