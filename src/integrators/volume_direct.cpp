#include "integrators/volume_direct.h"

#include "integrators/guided_direction.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/sampling.h"
#include "integrators/visibility.h"
#include "lights/area_light_sampling.h"
#include "lights/equiangular.h"
#include "lights/light_reach.h"
#include "lights/light_sample.h"

namespace caligo {
namespace {

using sample_dim::bounce;

// Equiangular sampling over the part of [t0, t1] the light reaches (lights/light_reach.h: a
// spot's cone, a range sphere, a one-sided area light's front half-space). Its pdf is zero
// elsewhere, where the integrand is zero too; density sampling still covers all of [t0, t1].
// None when the light reaches no part of the segment (then density sampling alone).
std::optional<EquiangularSetup> reach_equiangular_setup(const Light& light, const Ray& ray, Vec3 centre,
                                                        float t0, float t1) {
  if (!light_sampling_options().clip_equiangular)
    return make_equiangular_setup(ray.origin, ray.direction, centre, t0, t1);
  const auto reach = light_reach(light, ray.origin, ray.direction, t0, t1);
  if (!reach || !(reach->t1 > reach->t0)) return std::nullopt;
  return make_equiangular_setup(ray.origin, ray.direction, centre, reach->t0, reach->t1);
}

// f(t) / p_light: the light arriving at x(t) and scattered back along the ray, for one light
// sample at x(t), before dividing by the distance pdf.
RGB scattered_light(const PathContext& ctx, const Ray& ray, const TransmittanceRecord& record, int light_index,
                    float pick_pmf, float t, Vec2 u_light, const ShadowMedium& shadow) {
  const Scene& scene = ctx.scene;
  const int index = record.find_step(t);
  if (index < 0) return RGB(0.0f);
  const MarchStep& step = record.steps()[size_t(index)];
  if (step.sigma_s.is_black()) return RGB(0.0f);
  const Vec3 x = ray.at(t);
  const auto ls = sample_light(scene.lights()[size_t(light_index)], x, u_light);
  if (!ls || ls->radiance.is_black() || !(ls->pdf > 0.0f)) return RGB(0.0f);
  const RGB phase = mixed_phase_eval(record.lobes(step), ray.direction, ls->wi);
  if (phase.is_black()) return RGB(0.0f);
  bool through_interface = false;
  const RGB tr = light_transmittance(scene, x, x, *ls, scene.casts_shadows(light_index), shadow, ctx.scratch,
                                     ctx.counters, t, &through_interface);
  if (tr.is_black()) return RGB(0.0f);
  const float light_pdf_sa = pick_pmf * ls->pdf;
  // Deferred connections have no MIS partner: phase-sampled light hits from media count zero then.
  const float w =
      ls->delta || through_interface || ctx.settings.deferred_nee > 0
          ? 1.0f
          : power_heuristic(1, light_pdf_sa, 1, phase_sampling_pdf(ctx, x, record.lobes(step), ray.direction, ls->wi));
  return step.sigma_s * record.transmittance(t) * tr * ls->radiance * phase * (w / light_pdf_sa);
}

}  // namespace

RGB mixed_phase_eval(std::span<const PhaseLobe> lobes, Vec3 wo, Vec3 wi) {
  RGB sum;
  for (const PhaseLobe& lobe : lobes) sum += lobe.weight * phase_eval(lobe.phase, wo, wi);
  return sum;
}

float mixed_phase_pdf(std::span<const PhaseLobe> lobes, Vec3 wo, Vec3 wi) {
  if (lobes.size() == 1) return phase_pdf(lobes[0].phase, wo, wi);
  float sum = 0.0f, total = 0.0f;
  for (const PhaseLobe& lobe : lobes) {
    sum += lobe.weight.average() * phase_pdf(lobe.phase, wo, wi);
    total += lobe.weight.average();
  }
  return total > 0.0f ? sum / total : 0.0f;
}

MixedPhaseSample sample_mixed_phase(std::span<const PhaseLobe> lobes, Vec3 wo, float u_lobe, Vec2 u) {
  if (lobes.size() == 1) {
    const PhaseSample s = phase_sample(lobes[0].phase, wo, u);
    return {s.wi, lobes[0].weight, s.pdf};  // weight 1 in every channel that scatters
  }
  float total = 0.0f;
  for (const PhaseLobe& lobe : lobes) total += lobe.weight.average();
  size_t chosen = 0;
  for (float acc = 0.0f; chosen + 1 < lobes.size(); ++chosen) {
    acc += lobes[chosen].weight.average() / total;
    if (u_lobe < acc) break;
  }
  const Vec3 wi = phase_sample(lobes[chosen].phase, wo, u).wi;
  const float pdf = mixed_phase_pdf(lobes, wo, wi);
  return {wi, pdf > 0.0f ? mixed_phase_eval(lobes, wo, wi) / pdf : RGB(0.0f), pdf};
}

namespace {

// In-scattered light along a marched segment from one chosen light (volume_direct_light).
RGB connect_segment(const PathContext& ctx, const Ray& ray, const TransmittanceRecord& record, int depth,
                    bool secondary, LightChoice choice) {
  const Scene& scene = ctx.scene;
  const Sampler& sampler = ctx.sampler;
  const DistanceSampling strategy = ctx.settings.distance_sampling;
  const int light_index = choice.light;
  const float pick_pmf = choice.pmf;
  const Light& light = scene.lights()[size_t(light_index)];

  const auto centre = light_centre(light);
  std::optional<EquiangularDistribution> eq;
  if (centre && strategy != DistanceSampling::kDensity)
    if (const auto setup = reach_equiangular_setup(light, ray, *centre, record.t_begin(), record.t_end()))
      eq.emplace(*setup);
  // Equiangular sampling cancels the 1/r^2 that dominates the integrand near a light; density
  // sampling is the safety net where transmittance, not distance to the light, shapes the
  // integrand. kMis gives equiangular 0.95 of the samples on an optically thin segment (density
  // sampling is then nearly uniform in distance, a poor match near a light) down to 0.75 (the
  // former fixed share, kMisFixed) from optical depth 1 up.
  float equiangular_share = 0.0f;
  if (eq) {
    if (strategy == DistanceSampling::kMis) {
      const float t_end = record.transmittance_end().average();
      const float depth = t_end > 0.0f ? -std::log(t_end) : 1.0f;
      equiangular_share = 0.95f - 0.2f * std::min(depth, 1.0f);
    } else {
      equiangular_share = strategy == DistanceSampling::kMisFixed ? 0.75f : 1.0f;
    }
  }

  // One 2D sample chooses the strategy (x) and the distance (y), so the pairs stay stratified.
  const Vec2 u = sampler.get_2d(bounce(depth, sample_dim::kDistanceSample));
  float t;
  if (u.x < equiangular_share) {
    t = eq->sample(u.y);
  } else {
    const auto ds =
        record.sample_scatter_density(
            record.grey() ? 0.0f : sampler.get_1d(bounce(depth, sample_dim::kDensityChannel)), u.y);
    if (!ds) return RGB(0.0f);
    t = ds->t;
  }
  // One-sample MIS with the balance heuristic: the estimate divides by the mixture's density.
  const float pdf = (eq ? equiangular_share * eq->pdf(t) : 0.0f) +
                    (1.0f - equiangular_share) * record.scatter_density_pdf(t);
  if (!(pdf > 0.0f)) return RGB(0.0f);
  return scattered_light(ctx, ray, record, light_index, pick_pmf, t,
                         is_delta(light) ? Vec2{0.5f, 0.0f} : sampler.get_2d(bounce(depth, sample_dim::kVolumeLightPosition)),
                         shadow_medium(ctx, depth, secondary, sample_dim::kDistanceSample)) /
         pdf;
}

}  // namespace

RGB volume_direct_light(const PathContext& ctx, const Ray& ray, const TransmittanceRecord& record, int depth,
                        bool secondary) {
  if (record.scatter_weight_total() <= 0.0f) return RGB(0.0f);
  const LightSampler& lights = ctx.lights;
  const float u = lights.needs_random() ? ctx.sampler.get_1d(bounce(depth, sample_dim::kVolumeLightSelect)) : 0.0f;
  RGB sum(0.0f);
  for (const LightChoice& choice : lights.choose_segment(light_choice_segment(ray, record), u))
    sum += connect_segment(ctx, ray, record, depth, secondary, choice);
  return sum;
}

namespace {

RGB connect_point(const PathContext& ctx, Vec3 x, Vec3 direction, std::span<const PhaseLobe> lobes, int vertex,
                  float segment_t, LightChoice choice) {
  const Sampler& sampler = ctx.sampler;
  const Light& light = ctx.scene.lights()[size_t(choice.light)];
  const auto ls = sample_light(
      light, x, is_delta(light) ? Vec2{0.5f, 0.0f} : sampler.get_2d(bounce(vertex, sample_dim::kVolumeLightPosition)));
  if (!ls || ls->radiance.is_black() || !(ls->pdf > 0.0f)) return RGB(0.0f);
  const RGB phase = mixed_phase_eval(lobes, direction, ls->wi);
  if (phase.is_black()) return RGB(0.0f);
  bool through_interface = false;
  const RGB tr = light_transmittance(ctx.scene, x, x, *ls, ctx.scene.casts_shadows(choice.light),
                                     shadow_medium(ctx, vertex, true, sample_dim::kDistanceSample), ctx.scratch,
                                     ctx.counters, segment_t, &through_interface);
  if (tr.is_black()) return RGB(0.0f);
  const float light_pdf_sa = choice.pmf * ls->pdf;
  const float w = ls->delta || through_interface || ctx.settings.deferred_nee > 0
                      ? 1.0f
                      : power_heuristic(1, light_pdf_sa, 1, phase_sampling_pdf(ctx, x, lobes, direction, ls->wi));
  return phase * tr * ls->radiance * (w / light_pdf_sa);
}

}  // namespace

RGB point_volume_direct_light(const PathContext& ctx, Vec3 x, Vec3 direction, std::span<const PhaseLobe> lobes,
                              int vertex, float segment_t) {
  const float u =
      ctx.lights.needs_random() ? ctx.sampler.get_1d(bounce(vertex, sample_dim::kVolumeLightSelect)) : 0.0f;
  RGB sum(0.0f);
  for (const LightChoice& choice : ctx.lights.choose(x, Vec3(0.0f), u))
    sum += connect_point(ctx, x, direction, lobes, vertex, segment_t, choice);
  return sum;
}

}  // namespace caligo
