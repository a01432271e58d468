#include "integrators/emission_direct.h"

#include "integrators/guided_direction.h"

#include <cmath>

#include "core/sampling.h"
#include "integrators/volume_direct.h"
#include "materials/bsdf.h"

namespace caligo {
namespace {

struct Scattered {
  RGB f;        // phase function, or BSDF times |cos|
  float pdf;    // of sampling wi there (solid angle)
  Vec3 origin;  // where the gathering ray starts
};

// The vertex's scattering towards wi; f is black where no bounce could go (the far side of an
// opaque surface: bounce rays there are rejected too).
// The pdf is the vertex's own sampling density (guided or not), as the bounce ray's MIS weight has it.
Scattered scatter_towards(const PathContext& ctx, const EmissionVertex& v, Vec3 wi) {
  if (!v.surface)
    return {mixed_phase_eval(v.lobes, v.direction, wi), phase_sampling_pdf(ctx, v.p, v.lobes, v.direction, wi), v.p};
  const SurfaceInteraction& si = *v.surface;
  if (dot(si.ng, wi) * dot(si.ng, v.direction) <= 0.0f) return {RGB(0.0f), 0.0f, si.p};
  return {bsdf_eval(si.material->bsdf, si.ns, v.direction, wi) * abs_dot(si.ns, wi),
          bsdf_sampling_pdf(ctx, si.p, si.material->bsdf, si.ns, v.direction, wi), offset_ray_origin(si.p, si.ng, wi)};
}

}  // namespace

RGB emission_direct_light(const PathContext& ctx, const EmissionVertex& v, int vertex) {
  if (!ctx.emission) return RGB(0.0f);
  const Sampler& sampler = ctx.sampler;
  using sample_dim::emission;
  const Vec2 uxy = sampler.get_2d(emission(vertex, sample_dim::kEmissionPointXY));
  const auto y = ctx.emission->sample(sampler.get_1d(emission(vertex, sample_dim::kEmissionBlock)),
                                      Vec3(uxy.x, uxy.y, sampler.get_1d(emission(vertex, sample_dim::kEmissionPointZ))));
  if (!y) return RGB(0.0f);
  const Vec3 to = y->p - v.p;
  const float r = length(to);
  if (!(r > 0.0f) || !std::isfinite(r)) return RGB(0.0f);
  const Vec3 wi = to / r;
  const Scattered s = scatter_towards(ctx, v, wi);
  if (s.f.is_black()) return RGB(0.0f);
  const float p_e = ctx.emission->direction_pdf(v.p, wi);
  if (!(p_e > 0.0f)) return RGB(0.0f);
  // The line's emission up to the first surface that is not null, as the bounce ray would see it.
  Ray line{s.origin, wi, 0.0f, kInfinity};
  std::vector<SurfaceHit>& layers = ctx.scratch.line_layers;
  layers.clear();
  if (const auto hit = nearest_non_null_hit(ctx.scene, line, kMaxNullCrossings, &ctx.counters.rays,
                                            ctx.scene.has_transparent_surfaces() ? &layers : nullptr))
    line.tmax = hit->t;
  // Partly transparent surfaces on the way pass 1 - opacity of what lies behind them.
  const float jitter = sampler.get_1d(emission(vertex, sample_dim::kEmissionJitter));
  RGB gathered;
  float through = 1.0f;
  Ray piece = line;
  for (size_t i = 0; i <= layers.size() && through > 0.0f; ++i) {
    piece.tmax = i < layers.size() ? layers[i].t : line.tmax;
    if (piece.tmax > piece.tmin)
      gathered += march_emission(ctx.scene.volumes(), piece, jitter, ctx.scratch.march_settings, ctx.scratch.march) *
                  through;
    if (i < layers.size()) {
      through *= 1.0f - ctx.scene.opacity(layers[i]);
      piece.tmin = layers[i].t;
    }
  }
  if (gathered.is_black()) return RGB(0.0f);
  return s.f * gathered * (power_heuristic(1, p_e, 1, s.pdf) / p_e);
}

float emission_bounce_weight(const PathContext& ctx, Vec3 x, Vec3 wi, float scatter_pdf) {
  if (!ctx.emission) return 1.0f;
  return power_heuristic(1, scatter_pdf, 1, ctx.emission->direction_pdf(x, wi));
}

}  // namespace caligo
