#include "integrators/guided_direction.h"

namespace caligo {

using sample_dim::bounce;
using sample_dim::guiding;

namespace {

// Only a BSDF with a density can be mixed with the guide (a mirror or glass has a Dirac delta).
bool guidable(const Bsdf& bsdf) { return std::holds_alternative<DiffuseBsdf>(bsdf); }

}  // namespace

namespace {

// A path stops guiding once its guided directions, taken together, have raised its throughput
// more than 2x above what native sampling would carry (PathScratch::guided_growth). One-sample
// MIS bounds each vertex's factor by 1 / (1 - alpha), but in a dense, bright medium those factors
// multiply over hundreds of events: without the bound, `sss` under volume guiding had rare
// paths of huge weight (image means scattered 4x wider than unguided at 64 spp, most runs low)
// and `lamp-in-fog` 11 % more error per sample. The choice depends only on the path so far, which
// also fixes every MIS weight at the vertex (they call the same function), so it is unbiased.
constexpr float kMaxGuidedGrowth = 2.0f;

bool may_guide(const PathContext& ctx) { return ctx.scratch.guided_growth <= kMaxGuidedGrowth; }

}  // namespace

const DirectionalTree* surface_guide(const PathContext& ctx, Vec3 x, const Bsdf& bsdf) {
  return ctx.guide && ctx.guide_surfaces && guidable(bsdf) && may_guide(ctx) ? ctx.guide->at(x) : nullptr;
}

const DirectionalTree* volume_guide(const PathContext& ctx, Vec3 x) {
  return ctx.guide && ctx.guide_volumes && may_guide(ctx) ? ctx.guide->at(x) : nullptr;
}

bool volume_guides_distances(const PathContext& ctx) {
  return ctx.guide && ctx.guide_volumes && may_guide(ctx) && ctx.guide->completed_iterations() > 0;
}

void note_guided_sample(const PathContext& ctx, float pdf_native, float pdf) {
  if (pdf > 0.0f) ctx.scratch.guided_growth *= pdf_native / pdf;
}

namespace {

// The one-sample choice both mixtures make: a direction from the guide with probability alpha
// (nullopt otherwise: the caller samples its native density with the dimensions it always uses).
std::optional<Vec3> guided_choice(const Sampler& sampler, const DirectionalTree& guide, float alpha, int vertex) {
  if (!(alpha > 0.0f && sampler.get_1d(guiding(vertex, sample_dim::kGuideChoice)) < alpha)) return std::nullopt;
  float unused = 0.0f;  // the evaluated density is used instead, so that both agree on a leaf's edge
  return guide.sample(sampler.get_2d(guiding(vertex, sample_dim::kGuideDirection)), &unused);
}

// The mixture's density at wi: the guide's share of its evaluated density plus the native rest.
float mixture_pdf(const DirectionalTree& guide, float alpha, Vec3 wi, float native) {
  return alpha * guide.pdf(wi) + (1.0f - alpha) * native;
}

}  // namespace

std::optional<BsdfSample> guided_bsdf_sample(const PathContext& ctx, const DirectionalTree& guide, const Bsdf& bsdf,
                                             Vec3 n, Vec3 wo, int vertex) {
  const Sampler& sampler = ctx.sampler;
  const float alpha = guide.fraction(true);
  std::optional<Vec3> wi = guided_choice(sampler, guide, alpha, vertex);
  if (!wi) {
    const auto bs = bsdf_sample(bsdf, n, wo, sampler.get_1d(bounce(vertex, sample_dim::kBsdfLobe)),
                                sampler.get_2d(bounce(vertex, sample_dim::kBsdfDirection)));
    if (!bs || alpha == 0.0f) return bs;
    wi = bs->wi;
  }
  const float pdf = mixture_pdf(guide, alpha, *wi, bsdf_pdf(bsdf, n, wo, *wi));
  const RGB f = bsdf_eval(bsdf, n, wo, *wi) * abs_dot(n, *wi);
  if (!(pdf > 0.0f) || f.is_black()) return std::nullopt;
  return BsdfSample{*wi, f / pdf, pdf, false};
}

MixedPhaseSample guided_phase_sample(const PathContext& ctx, const DirectionalTree& guide,
                                     std::span<const PhaseLobe> lobes, Vec3 wo, int vertex) {
  const Sampler& sampler = ctx.sampler;
  const float alpha = guide.fraction(false);
  std::optional<Vec3> wi = guided_choice(sampler, guide, alpha, vertex);
  if (!wi) {
    const MixedPhaseSample ps = sample_mixed_phase(
        lobes, wo, lobes.size() > 1 ? sampler.get_1d(bounce(vertex, sample_dim::kPhaseLobe)) : 0.0f,
        sampler.get_2d(bounce(vertex, sample_dim::kPhaseDirection)));
    if (alpha == 0.0f) return ps;
    wi = ps.wi;
  }
  const float pdf = mixture_pdf(guide, alpha, *wi, mixed_phase_pdf(lobes, wo, *wi));
  const RGB f = mixed_phase_eval(lobes, wo, *wi);
  return {*wi, pdf > 0.0f ? f / pdf : RGB(0.0f), pdf};
}

float phase_sampling_pdf(const PathContext& ctx, Vec3 x, std::span<const PhaseLobe> lobes, Vec3 wo, Vec3 wi) {
  const float native = mixed_phase_pdf(lobes, wo, wi);
  const DirectionalTree* guide = volume_guide(ctx, x);
  const float alpha = guide ? guide->fraction(false) : 0.0f;
  if (alpha == 0.0f) return native;
  return mixture_pdf(*guide, alpha, wi, native);
}

float bsdf_sampling_pdf(const PathContext& ctx, Vec3 x, const Bsdf& bsdf, Vec3 n, Vec3 wo, Vec3 wi) {
  const float native = bsdf_pdf(bsdf, n, wo, wi);
  const DirectionalTree* guide = surface_guide(ctx, x, bsdf);
  const float alpha = guide ? guide->fraction(true) : 0.0f;
  if (alpha == 0.0f) return native;
  return mixture_pdf(*guide, alpha, wi, native);
}

bool trains_surface(const PathContext& ctx, const Bsdf& bsdf) {
  return ctx.train && ctx.guide_surfaces && guidable(bsdf);
}

bool trains_volume(const PathContext& ctx) { return ctx.train && ctx.guide_volumes; }

void remember_guided_vertex(const PathContext& ctx, Vec3 x, bool surface, Vec3 wi, RGB weight, float pdf,
                            float pdf_native, RGB throughput, const PathSample& out) {
  if (pdf > 0.0f && !throughput.is_black())
    ctx.scratch.guided.push_back(
        {x, wi, pdf, (weight * pdf).average(), pdf_native, surface, throughput, out.beauty()});
}

void train_guide(const PathContext& ctx, const PathSample& out) {
  const RGB image = out.beauty();
  for (const GuidedVertex& v : ctx.scratch.guided) {
    // The radiance along wi, per channel the throughput carries, averaged.
    const RGB added = image - v.image_before;
    double radiance = 0.0;
    int channels = 0;
    for (int c = 0; c < 3; ++c)
      if (v.throughput[c] > 0.0f) {
        radiance += double(added[c]) / double(v.throughput[c]);
        ++channels;
      }
    if (channels > 0)
      ctx.guide->record(v.x, GuidingRecord{v.wi, radiance / channels, v.f, v.pdf_native, v.pdf, v.surface});
  }
}

}  // namespace caligo
