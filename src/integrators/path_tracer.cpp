#include "integrators/path_tracer.h"

#include <algorithm>

#include "core/sampling.h"
#include "lights/light_sample.h"
#include "materials/bsdf.h"

namespace caligo {
namespace {

using sample_dim::bounce;

// Shadow rays stop this fraction short of an area-light sample so they do not hit the light.
constexpr float kShadowEpsilon = 1e-4f;

// The state carried from one bounce to the next.
struct PathState {
  RGB throughput{1.0f};
  bool specular_bounce = true;  // the camera ray counts as specular: no MIS on what it sees
  float bsdf_pdf = 0.0f;        // pdf of the direction that produced the current ray
  Vec3 bsdf_origin;             // where that direction was sampled
};

float mis_weight_for_hit(const Scene& scene, const PathState& state, int light, Vec3 wi, Vec3 p, Vec3 n) {
  if (state.specular_bounce) return 1.0f;
  const float light_pdf_sa =
      scene.light_selection_pmf(light) * light_pdf(scene.lights()[size_t(light)], state.bsdf_origin, wi, p, n);
  return power_heuristic(1, state.bsdf_pdf, 1, light_pdf_sa);
}

RGB escaped(const Scene& scene, const PathState& state, Vec3 w) {
  RGB sum;
  for (int i : scene.infinite_lights()) {
    const RGB le = escaped_radiance(scene.lights()[size_t(i)], w);
    if (!le.is_black()) sum += le * mis_weight_for_hit(scene, state, i, w, {}, {});
  }
  return sum;
}

RGB emitted(const Scene& scene, const PathState& state, const SurfaceInteraction& si, Vec3 wo) {
  if (si.material->emission.is_black()) return RGB(0.0f);
  const bool front = dot(si.ng, wo) > 0.0f || si.material->two_sided_emission;
  if (!front) return RGB(0.0f);
  if (si.light < 0) return si.material->emission;
  return si.material->emission * mis_weight_for_hit(scene, state, si.light, -wo, si.p, si.ng);
}

// Next-event estimation: one light chosen in proportion to power, one point on it.
RGB sample_direct(const Scene& scene, const SurfaceInteraction& si, Vec3 wo, const Sampler& sampler, int depth,
                  PathCounters& counters) {
  const DiscreteDistribution& selection = scene.light_selection();
  if (selection.empty()) return RGB(0.0f);
  float pick_pmf = 0.0f;
  const int index = selection.sample(sampler.get_1d(bounce(depth, sample_dim::kLightSelect)), &pick_pmf);
  const Light& light = scene.lights()[size_t(index)];
  const auto ls = sample_light(light, si.p, sampler.get_2d(bounce(depth, sample_dim::kLightPosition)));
  if (!ls || ls->radiance.is_black() || !(ls->pdf > 0.0f)) return RGB(0.0f);
  const RGB f = bsdf_eval(si.material->bsdf, si.ns, wo, ls->wi) * abs_dot(si.ns, ls->wi);
  if (f.is_black() || dot(si.ng, ls->wi) * dot(si.ng, wo) <= 0.0f) return RGB(0.0f);

  Ray shadow{offset_ray_origin(si.p, si.ng, ls->wi), ls->wi, 0.0f, kInfinity};
  if (std::isfinite(ls->distance)) {
    shadow.direction = si.p + ls->wi * ls->distance - shadow.origin;
    shadow.tmax = 1.0f - kShadowEpsilon;
  }
  ++counters.rays;
  if (scene.surfaces().occluded(shadow)) return RGB(0.0f);
  const float light_pdf_sa = pick_pmf * ls->pdf;
  const float weight =
      ls->delta ? 1.0f : power_heuristic(1, light_pdf_sa, 1, bsdf_pdf(si.material->bsdf, si.ns, wo, ls->wi));
  return f * ls->radiance * (weight / light_pdf_sa);
}

// Returns false when the path ends (absorbed or rouletted).
bool russian_roulette(PathState& state, const Sampler& sampler, int depth, const PathSettings& settings) {
  if (depth < settings.russian_roulette_depth) return true;
  const float survive = std::min(1.0f, state.throughput.max_component());
  if (sampler.get_1d(bounce(depth, sample_dim::kRussianRoulette)) >= survive) return false;
  state.throughput *= 1.0f / survive;
  return true;
}

void record_first_hit(PathSample& out, const SurfaceInteraction& si, float t) {
  out.alpha = 1.0f;
  out.hit_t = t;
  out.normal = si.ns;
  out.albedo = bsdf_albedo(si.material->bsdf);
}

}  // namespace

PathSample trace_path(const Scene& scene, Ray ray, const Sampler& sampler, const PathSettings& settings,
                      PathCounters& counters) {
  PathSample out;
  PathState state;
  float t_travelled = 0.0f;  // along the camera ray, across null surfaces
  int null_crossings = 0;
  for (int depth = 0;;) {
    ++counters.rays;
    const auto hit = scene.surfaces().intersect(ray);
    if (!hit) {
      out.radiance += state.throughput * escaped(scene, state, ray.direction);
      break;
    }
    const SurfaceInteraction si = scene.interaction(ray, *hit);
    const Vec3 wo = -ray.direction;
    if (std::holds_alternative<NullBsdf>(si.material->bsdf)) {
      if (++null_crossings > settings.max_null_crossings) break;
      if (depth == 0) t_travelled += hit->t;
      ray = {offset_ray_origin(si.p, si.ng, ray.direction), ray.direction, 0.0f, kInfinity};
      continue;
    }
    if (depth == 0) record_first_hit(out, si, t_travelled + hit->t);
    out.radiance += state.throughput * emitted(scene, state, si, wo);
    if (depth >= settings.max_depth) break;

    if (!is_specular(si.material->bsdf))
      out.radiance += state.throughput * sample_direct(scene, si, wo, sampler, depth, counters);

    const auto bs = bsdf_sample(si.material->bsdf, si.ns, wo, sampler.get_1d(bounce(depth, sample_dim::kBsdfLobe)),
                                sampler.get_2d(bounce(depth, sample_dim::kBsdfDirection)));
    if (!bs || bs->weight.is_black()) break;
    // Reject directions the shading normal allows but the geometry does not (light leaks).
    const bool transmits = dot(si.ng, bs->wi) * dot(si.ng, wo) < 0.0f;
    if (transmits && !std::holds_alternative<DielectricBsdf>(si.material->bsdf)) break;
    state.throughput *= bs->weight;
    state.specular_bounce = bs->specular;
    state.bsdf_pdf = bs->pdf;
    state.bsdf_origin = si.p;
    ray = {offset_ray_origin(si.p, si.ng, bs->wi), bs->wi, 0.0f, kInfinity};
    if (!russian_roulette(state, sampler, depth, settings)) break;
    ++depth;
  }
  return out;
}

}  // namespace caligo
