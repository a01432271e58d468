#include "integrators/path_tracer.h"

#include <algorithm>

#include "core/sampling.h"
#include "integrators/interface_eta.h"
#include "integrators/visibility.h"
#include "integrators/volume_direct.h"
#include "lights/light_sample.h"
#include "materials/bsdf.h"

namespace caligo {
namespace {

using sample_dim::bounce;

// The state carried from one scattering event to the next.
struct PathState {
  RGB throughput{1.0f};
  bool specular_bounce = true;  // the camera ray counts as specular: no MIS on what it sees
  // Only specular events so far (the camera ray, mirrors, glass): what a ray sees now is what
  // the camera sees, so an environment with visible = false shows black to it.
  bool camera_view = true;
  float scatter_pdf = 0.0f;     // solid-angle pdf of the direction that produced the current ray
  Vec3 scatter_origin;          // where that direction was sampled
  // The light choice next-event estimation made at that vertex, whose pmf the MIS weight of a
  // light hit needs: at a surface, pmf(scatter_origin, scatter_normal); after scattering in a
  // medium, pmf_segment(scatter_segment), the segment volume NEE chose its light for.
  const LightSampler* light_sampler = nullptr;
  bool deferred_nee = false;  // PathSettings::deferred_nee > 0
  Vec3 scatter_normal;
  bool scattered_in_medium = false;
  Ray scatter_segment;
  int events = 0;               // scattering events so far (surface and volume, every one)
  int surface_bounces = 0;
  int volume_bounces = 0;
  // A run of consecutive scattering events in media counts as ONE bounce against max_bounces
  // (max_volume_bounces bounds the events inside runs): so max_bounces 1 is direct light only,
  // surfaces or media, and a long chain of scattering in fog costs a path one surface bounce.
  int volume_runs = 0;
  bool in_volume_run = false;
  // Real crossings of medium boundaries (priority null surfaces): not events, but each starts a
  // new segment whose free-flight and NEE samples must not reuse the previous segment's.
  int boundary_crossings = 0;
  // Light-layer bookkeeping (integrators/path_sample.h): non-specular events so far and where
  // the first of them happened.
  int nonspecular_events = 0;
  bool first_event_in_medium = false;
  // Alpha: what of the background the camera sees through this path, so far (1 - alpha).
  float visibility = 0.0f;
  bool first_hit_recorded = false;

  // The sampler's vertex index: events plus boundary crossings (= events without nested media).
  int vertex() const { return events + boundary_crossings; }

  // Whether the path may have another bounce of PathLimits::max_bounces (a surface bounce or the
  // start of a volume run).
  bool may_bounce(int max_bounces) const { return surface_bounces + volume_runs < max_bounces; }

  // The layer of light that reaches the camera along the path as it is: emission and light hits
  // (`seen` is the layer when the camera sees it directly).
  LightKind arriving(LightKind seen) const {
    if (nonspecular_events == 0) return seen;
    const bool direct = nonspecular_events == 1;
    if (first_event_in_medium) return direct ? LightKind::kVolumeDirect : LightKind::kVolumeIndirect;
    return direct ? LightKind::kSurfaceDirect : LightKind::kSurfaceIndirect;
  }
  // The layer of a light connection made at a new non-specular event (in a medium or not).
  LightKind connected(bool in_medium) const {
    const bool medium_first = nonspecular_events == 0 ? in_medium : first_event_in_medium;
    const bool direct = nonspecular_events == 0;
    if (medium_first) return direct ? LightKind::kVolumeDirect : LightKind::kVolumeIndirect;
    return direct ? LightKind::kSurfaceDirect : LightKind::kSurfaceIndirect;
  }
  void count_nonspecular_event(bool in_medium) {
    if (nonspecular_events == 0) first_event_in_medium = in_medium;
    ++nonspecular_events;
  }
};

// The probability that next-event estimation at the previous vertex chose `light`.
float light_choice_pmf(const PathState& state, int light) {
  return state.scattered_in_medium
             ? state.light_sampler->pmf_segment(state.scatter_segment, light)
             : state.light_sampler->pmf(state.scatter_origin, state.scatter_normal, light);
}

float mis_weight_for_hit(const Scene& scene, const PathState& state, int light, Vec3 wi, Vec3 p, Vec3 n) {
  if (state.specular_bounce) return 1.0f;
  if (state.deferred_nee && state.scattered_in_medium) return 0.0f;  // deferred connections count it
  const float light_pdf_sa =
      light_choice_pmf(state, light) * light_pdf(scene.lights()[size_t(light)], state.scatter_origin, wi, p, n);
  return power_heuristic(1, state.scatter_pdf, 1, light_pdf_sa);
}

// Cycles' camera-ray visibility of the world, extended through specular chains (see
// EnvironmentLight::visible): NEE never reaches those rays, so lighting is unchanged.
bool hidden_from_view(const Light& light, const PathState& state) {
  const auto* env = std::get_if<EnvironmentLight>(&light);
  return env && !env->visible && state.camera_view;
}

RGB escaped(const Scene& scene, const PathState& state, Vec3 w) {
  RGB sum;
  for (int i : scene.infinite_lights()) {
    if (hidden_from_view(scene.lights()[size_t(i)], state)) continue;
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

// The normal surface light choice uses: light is only taken from the side wo is on (the
// geometric test below), so lights behind the surface get no share.
Vec3 light_choice_normal(const SurfaceInteraction& si, Vec3 wo) { return face_forward(si.ng, wo); }

// Next-event estimation at a surface: one light chosen by the light sampler, one point on it.
RGB surface_direct_light(const Scene& scene, const LightSampler& lights, const SurfaceInteraction& si, Vec3 wo,
                         const Sampler& sampler, int depth, PathScratch& scratch, PathCounters& counters) {
  // Random numbers that would not be used are not drawn (one light, a delta light's position).
  const LightChoice choice =
      lights.sample(si.p, light_choice_normal(si, wo),
                    lights.needs_random() ? sampler.get_1d(bounce(depth, sample_dim::kLightSelect)) : 0.0f);
  if (choice.light < 0) return RGB(0.0f);
  const int index = choice.light;
  const float pick_pmf = choice.pmf;
  const Light& light = scene.lights()[size_t(index)];
  const auto ls = sample_light(
      light, si.p, is_delta(light) ? Vec2(0.5f) : sampler.get_2d(bounce(depth, sample_dim::kLightPosition)));
  if (!ls || ls->radiance.is_black() || !(ls->pdf > 0.0f)) return RGB(0.0f);
  const RGB f = bsdf_eval(si.material->bsdf, si.ns, wo, ls->wi) * abs_dot(si.ns, ls->wi);
  if (f.is_black() || dot(si.ng, ls->wi) * dot(si.ng, wo) <= 0.0f) return RGB(0.0f);
  bool through_interface = false;
  const RGB tr = light_transmittance(scene, offset_ray_origin(si.p, si.ng, ls->wi), si.p, *ls,
                                     scene.casts_shadows(index), march_jitter(scene, sampler, depth), scratch,
                                     counters, kInfinity, &through_interface);
  if (tr.is_black()) return RGB(0.0f);
  const float light_pdf_sa = pick_pmf * ls->pdf;
  const float weight = ls->delta || through_interface
                           ? 1.0f
                           : power_heuristic(1, light_pdf_sa, 1, bsdf_pdf(si.material->bsdf, si.ns, wo, ls->wi));
  return f * tr * ls->radiance * (weight / light_pdf_sa);
}

// Returns false when the path ends (absorbed or rouletted).
bool russian_roulette(PathState& state, const Sampler& sampler, const PathSettings& settings) {
  if (state.events < settings.russian_roulette_depth) return true;
  const float survive = std::min(1.0f, state.throughput.max_component());
  if (survive >= 1.0f) return true;  // no draw: it could not end the path
  if (sampler.get_1d(bounce(state.vertex(), sample_dim::kRussianRoulette)) >= survive) return false;
  state.throughput *= 1.0f / survive;
  return true;
}

void record_first_hit(PathSample& out, const SurfaceInteraction& si, float t) {
  out.hit_t = t;
  out.normal = si.ns;
  out.albedo = bsdf_albedo(si.material->bsdf);
}

// Phase 1 for surfaces: the nearest hit that is not a null surface. Null surfaces are
// skipped along the same ray, so the volume segment in front of the hit stays one piece.
std::optional<SurfaceHit> nearest_opaque_hit(const Scene& scene, const Ray& ray, const PathSettings& settings,
                                             PathCounters& counters) {
  Ray probe = ray;
  for (int crossings = 0; crossings <= settings.max_null_crossings; ++crossings) {
    ++counters.rays;
    const auto hit = scene.surfaces().intersect(probe);
    if (!hit) return std::nullopt;
    if (!std::holds_alternative<NullBsdf>(scene.material(*hit).bsdf)) return hit;
    // Step past the null surface by a relative epsilon of its distance.
    probe.tmin = hit->t + std::max(1e-4f, hit->t * 1e-5f);
  }
  return std::nullopt;
}

// Phase 1 with the medium stack: the nearest hit that is seen. Off null surfaces are crossed as
// above; priority surfaces whose crossing the rules call false are crossed and queued in
// scratch.pending (applied to the stack once the path is known to get past them). Returns the
// first Off non-null surface or real priority crossing, whose crossing is NOT applied (a
// dielectric may reflect).
std::optional<SurfaceHit> nearest_visible_hit(const Scene& scene, const Ray& ray, const PathSettings& settings,
                                              PathScratch& scratch, PathCounters& counters) {
  scratch.pending.clear();
  scratch.work.assign(scratch.stack);
  Ray probe = ray;
  for (int crossings = 0; crossings <= settings.max_null_crossings; ++crossings) {
    ++counters.rays;
    const auto hit = scene.surfaces().intersect(probe);
    if (!hit) return std::nullopt;
    if (const auto entry = scene.medium_entry(hit->geom_id)) {
      if (scratch.work.peek(*entry).real) return hit;
      scratch.work.cross(*entry);
      scratch.pending.push_back({hit->t, *entry});
    } else if (!std::holds_alternative<NullBsdf>(scene.material(*hit).bsdf)) {
      return hit;
    }
    probe.tmin = hit->t + std::max(1e-4f, hit->t * 1e-5f);
  }
  return std::nullopt;
}

// The queued false crossings before t_limit join the path's stack; the queue empties.
void apply_pending(PathScratch& scratch, float t_limit) {
  for (const PendingCrossing& p : scratch.pending)
    if (p.t < t_limit) scratch.stack.cross(p.entry);
  scratch.pending.clear();
}

enum class SegmentOutcome { kScattered, kPassed, kAbsorbed };

// Phases 2 and 3 for the medium in front of the next surface (or to infinity).
// `medium`: the scene medium the stack puts the segment in (-1: none). On kScattered,
// *event_t is the collision's distance along the old ray.
SegmentOutcome integrate_medium(const Scene& scene, Ray& ray, float t_surface, const Sampler& sampler,
                                const PathSettings& settings, PathState& state, PathSample& out,
                                PathScratch& scratch, PathCounters& counters, int medium, float* event_t) {
  TransmittanceRecord& record = scratch.record;
  Ray segment = ray;
  segment.tmax = t_surface;
  march(scene.volumes(), segment, march_jitter(scene, sampler, state.vertex()), scratch.march_settings,
        scratch.march, record, medium);
  if (record.empty()) return SegmentOutcome::kPassed;
  if (state.events == 0) counters.camera_march_steps += record.steps().size();
  out.add(state.arriving(LightKind::kVolumeEmission), state.throughput * record.emission());
  // A path that has used up its surface bounces may not scatter in media either: max_bounces
  // bounds the whole path's surface events, and a scattering event after the last one
  // would lengthen it.
  const bool may_scatter = state.volume_bounces < settings.limits.max_volume_bounces &&
                           (state.in_volume_run || state.may_bounce(settings.limits.max_bounces));
  if (may_scatter && settings.deferred_nee <= 0) {
    // Segments that barely scatter (thin fog between two walls) contribute little in-scattered
    // light but cost two shadow rays: next-event estimation runs with a probability that
    // follows the segment's scattering probability, and is reweighted (unbiased roulette).
    const float nee_probability = std::min(1.0f, settings.volume_nee_scale * record.scatter_weight_total());
    const float u = nee_probability < 1.0f ? sampler.get_1d(bounce(state.vertex(), sample_dim::kVolumeNeeRoulette))
                                           : 0.0f;
    if (nee_probability > 0.0f && u < nee_probability)
      out.add(state.connected(true),
              state.throughput *
                      volume_direct_light(scene, *state.light_sampler, ray, record, sampler, state.vertex(),
                                          settings.distance_sampling, scratch, counters) /
                      nee_probability);
  }

  // Absorption by weight, not by chance (PathSettings::absorption_by_weight; implicit capture):
  // of the three fates of a path in the segment -- scatter (probability S = avg_c of the integral
  // of sigma_s,c T_c), pass (P = avg_c T_c at the end) or be absorbed (the rest) -- only the first
  // two are sampled, in proportion S : P, and both carry the surviving fraction S + P as weight.
  // A collision is drawn with density proportional to avg_c sigma_s,c T_c (the sampler light
  // connections use); passing carries the record's exact T. A purely absorbing medium (S = 0)
  // has zero variance; albedo 1 (S + P = 1) is exactly free-flight sampling. Sampling pass
  // against S alone (pass weight T / (1 - S)) was worse in dense, bright media: its passes carry
  // tiny weights that Russian roulette then turns into noise (3x the standard error on `sss`).
  // A path that may not scatter again just takes T.
  const float u = sampler.get_1d(bounce(state.vertex(), sample_dim::kFreeFlightDistance));
  // A grey record samples the same distance whichever channel is picked.
  const float u_channel =
      record.grey() ? 0.0f : sampler.get_1d(bounce(state.vertex(), sample_dim::kFreeFlightChannel));
  std::optional<DistanceSample> collision;
  if (settings.absorption_by_weight) {
    const RGB t_end = record.transmittance_end();
    const float scatter = may_scatter ? record.scatter_weight_total() : 0.0f, pass = t_end.average();
    const float survive = scatter + pass;
    const float p_scatter = survive > 0.0f ? scatter / survive : 0.0f;
    if (!(u < p_scatter)) {
      state.throughput *= p_scatter > 0.0f ? t_end * (survive / pass) : t_end;
      return state.throughput.is_black() ? SegmentOutcome::kAbsorbed : SegmentOutcome::kPassed;
    }
    collision = record.sample_scatter_density(u_channel, u / p_scatter);
    if (!collision) return SegmentOutcome::kAbsorbed;  // p_scatter > 0 implies a collision
    // The collision's density is p_scatter x pdf = avg_c sigma_s,c(t) T_c(t) / survive.
    collision->pdf *= p_scatter;
  } else {
    collision = record.sample_free_flight(u_channel, u);
    if (!collision) {
      const RGB t_end = record.transmittance_end();
      state.throughput *= t_end / t_end.average();
      return SegmentOutcome::kPassed;
    }
    if (!may_scatter) return SegmentOutcome::kAbsorbed;
  }
  const MarchStep& step = record.steps()[size_t(collision->step)];
  state.throughput *= step.sigma_s * record.transmittance(collision->t) / collision->pdf;
  if (state.throughput.is_black()) return SegmentOutcome::kAbsorbed;
  const Vec3 x = ray.at(collision->t);
  *event_t = collision->t;
  const RGB beta = state.throughput;  // at the vertex, before the phase sample (deferred NEE)
  const MixedPhaseSample ps = sample_mixed_phase(
      record, step, ray.direction,
      record.lobes(step).size() > 1 ? sampler.get_1d(bounce(state.vertex(), sample_dim::kPhaseLobe)) : 0.0f,
      sampler.get_2d(bounce(state.vertex(), sample_dim::kPhaseDirection)));
  state.throughput *= ps.weight;
  if (state.throughput.is_black()) return SegmentOutcome::kAbsorbed;
  // Kept only on the scattered outcome, which is where trace_path stores its medium stack.
  if (settings.deferred_nee > 0) {
    const auto lobes = record.lobes(step);
    scratch.deferred.push_back({x, ray.direction, beta, state.connected(true), uint32_t(scratch.deferred_lobes.size()),
                                uint32_t(lobes.size())});
    scratch.deferred_lobes.insert(scratch.deferred_lobes.end(), lobes.begin(), lobes.end());
  }
  state.specular_bounce = false;
  state.camera_view = false;
  state.scatter_pdf = ps.pdf;
  state.scatter_origin = x;
  state.scattered_in_medium = true;
  state.scatter_segment = light_choice_segment(ray, record);
  state.count_nonspecular_event(true);
  ray = {x, ps.wi, 0.0f, kInfinity};
  ++state.volume_bounces;
  if (!state.in_volume_run) ++state.volume_runs;
  state.in_volume_run = true;
  return SegmentOutcome::kScattered;
}


// Deferred next-event estimation (PathSettings::deferred_nee): `count` connections, each to a
// scattering vertex of the finished path chosen with probability q_i proportional to its
// throughput and weighted 1 / (count q_i); at the vertex, one light by the light sampler's
// point form and one point on it, the phase mixture stored with the vertex, and the shadow
// ray's transmittance (with the vertex's medium stack in nested scenes). Its random numbers
// come from the vertex indices after the path's last one.
void deferred_connections(const Scene& scene, const LightSampler& lights, const Sampler& sampler, int count,
                          int first_dim, bool nested, PathScratch& scratch, PathCounters& counters, PathSample& out) {
  double total = 0.0;
  for (const auto& v : scratch.deferred) total += double(v.beta.average());
  if (!(total > 0.0)) return;
  for (int k = 0; k < count; ++k) {
    const int dim = first_dim + k;
    // The vertex: inverse CDF over the throughputs.
    const double target = double(sampler.get_1d(bounce(dim, sample_dim::kFreeFlightChannel))) * total;
    size_t i = 0;
    double acc = double(scratch.deferred[0].beta.average());
    while (acc <= target && i + 1 < scratch.deferred.size()) acc += double(scratch.deferred[++i].beta.average());
    const auto& v = scratch.deferred[i];
    const float q = float(double(v.beta.average()) / total);
    if (!(q > 0.0f)) continue;
    const LightChoice choice = lights.sample(
        v.x, Vec3(0.0f), lights.needs_random() ? sampler.get_1d(bounce(dim, sample_dim::kVolumeLightSelect)) : 0.0f);
    if (choice.light < 0) continue;
    const Light& light = scene.lights()[size_t(choice.light)];
    const auto ls = sample_light(
        light, v.x, is_delta(light) ? Vec2(0.5f) : sampler.get_2d(bounce(dim, sample_dim::kVolumeLightPosition)));
    if (!ls || ls->radiance.is_black() || !(ls->pdf > 0.0f)) continue;
    RGB phase;
    for (uint32_t l = 0; l < v.lobe_count; ++l) {
      const PhaseLobe& lobe = scratch.deferred_lobes[v.first_lobe + l];
      phase += lobe.weight * phase_eval(lobe.phase, v.wo, ls->wi);
    }
    if (phase.is_black()) continue;
    if (nested) {
      scratch.stack.assign(scratch.deferred_stacks[i]);
      scratch.pending.clear();
    }
    const RGB tr = light_transmittance(scene, v.x, v.x, *ls, scene.casts_shadows(choice.light),
                                       march_jitter(scene, sampler, dim), scratch, counters);
    if (tr.is_black()) continue;
    out.add(v.kind, v.beta * phase * tr * ls->radiance * (1.0f / (choice.pmf * ls->pdf * float(count) * q)));
  }
}

}  // namespace

float march_jitter(const Scene& scene, const Sampler& sampler, int depth) {
  return scene.volumes().all_homogeneous() ? 0.5f : sampler.get_1d(bounce(depth, sample_dim::kMarchJitter));
}

PathSample trace_path(const Scene& scene, Ray ray, const Sampler& sampler, const PathSettings& settings,
                      PathCounters& counters, PathScratch& scratch) {
  PathSample out;
  PathState state;
  state.light_sampler = &scene.light_sampler(settings.light_sampler);
  state.deferred_nee = settings.deferred_nee > 0;
  scratch.deferred.clear();
  scratch.deferred_lobes.clear();
  // Scenes without priority surfaces take exactly the paths they took before nested media.
  const bool nested = scene.has_priority_objects();
  const bool has_volumes = !scene.volumes().empty() || scene.volumes().has_media();
  if (nested) {
    scratch.stack.assign(scene.camera_stack());
    scratch.pending.clear();
  }
  for (;;) {
    // A degenerate computation upstream (a NaN direction or weight) ends the path here
    // rather than poisoning the pixel; the film drops non-finite samples too.
    if (!is_finite(ray.direction) || !state.throughput.is_finite()) break;
    const auto hit = nested ? nearest_visible_hit(scene, ray, settings, scratch, counters)
                            : nearest_opaque_hit(scene, ray, settings, counters);
    // The camera ray itself (no event yet; null boundaries are not events) sees the background,
    // or a holdout, at the end of this segment: its share joins the visibility (1 - alpha)
    // whether or not the path then scatters on the way, so alpha behind a medium is exact, not
    // 0 or 1. Glass and mirrors are opaque to alpha, as in Arnold and Cycles by default: what is
    // seen in them is part of the render, not a hole onto the plate.
    const bool holdout_hit = hit && scene.is_holdout(hit->geom_id);
    const bool camera_ray = state.events == 0;
    const RGB throughput_in = state.throughput;  // integrate_medium changes it
    // The first surface the camera ray meets is recorded before the medium in front of it is
    // sampled: a camera path that scatters on the way still reports the surface behind.
    std::optional<SurfaceInteraction> hit_si;
    if (hit && state.events == 0 && !state.first_hit_recorded) {
      hit_si = scene.interaction(ray, *hit);
      if (!(nested && scene.medium_entry(hit->geom_id) && std::holds_alternative<NullBsdf>(hit_si->material->bsdf))) {
        record_first_hit(out, *hit_si, hit->t);
        state.first_hit_recorded = true;
      }
    }
    if (has_volumes) {
      float event_t = kInfinity;
      const SegmentOutcome outcome =
          integrate_medium(scene, ray, hit ? hit->t : kInfinity, sampler, settings, state, out, scratch, counters,
                           nested ? scratch.stack.current().medium : -1, &event_t);
      if (camera_ray) {
        // The throughput carries earlier segments' (coloured) transmittance: the channel average
        // of the product, not the product of averages.
        if (!hit || holdout_hit) state.visibility += (throughput_in * scratch.record.transmittance_end()).average();
        state.visibility += throughput_in.average() * scratch.record.holdout_total();
      }
      if (outcome == SegmentOutcome::kAbsorbed) break;
      if (outcome == SegmentOutcome::kScattered) {
        if (nested) apply_pending(scratch, event_t);
        if (nested && state.deferred_nee) {
          if (scratch.deferred_stacks.size() < scratch.deferred.size()) scratch.deferred_stacks.resize(scratch.deferred.size());
          scratch.deferred_stacks[scratch.deferred.size() - 1].assign(scratch.stack);
        }
        ++state.events;
        if (!russian_roulette(state, sampler, settings)) break;
        continue;
      }
    } else if (camera_ray && (!hit || holdout_hit)) {
      state.visibility += state.throughput.average();
    }
    if (nested) apply_pending(scratch, kInfinity);
    if (!hit) {
      out.add(state.arriving(LightKind::kBackground), state.throughput * escaped(scene, state, ray.direction));
      break;
    }
    // A holdout seen by the camera is a hole in the image (counted in the visibility above);
    // other paths see it as the surface it is (it still shadows and shows in reflections).
    if (holdout_hit && camera_ray) break;
    const SurfaceInteraction si = hit_si ? *hit_si : scene.interaction(ray, *hit);
    const Vec3 wo = -ray.direction;
    const std::optional<MediumEntry> entry = nested ? scene.medium_entry(hit->geom_id) : std::nullopt;
    if (entry && std::holds_alternative<NullBsdf>(si.material->bsdf)) {
      // A medium boundary the rules make real: the ray's medium changes, nothing is seen.
      scratch.stack.cross(*entry);
      if (++state.boundary_crossings > settings.max_null_crossings) break;
      ray = {offset_ray_origin(si.p, si.ng, ray.direction), ray.direction, 0.0f, kInfinity};
      continue;
    }
    out.add(state.arriving(LightKind::kSurfaceEmission), state.throughput * emitted(scene, state, si, wo));
    if (!state.may_bounce(settings.limits.max_bounces)) break;

    if (!is_specular(si.material->bsdf))
      out.add(state.connected(false),
              state.throughput * surface_direct_light(scene, *state.light_sampler, si, wo, sampler, state.vertex(),
                                                      scratch, counters));

    // A dielectric refracts with the IORs of the media actually on either side.
    const Bsdf* bsdf = &si.material->bsdf;
    Bsdf interface;
    if (const auto* d = std::get_if<DielectricBsdf>(bsdf); d && nested) {
      interface = DielectricBsdf{interface_eta(scratch.stack, entry, d->ior, dot(si.ng, wo) > 0.0f)};
      bsdf = &interface;
    }
    const auto bs = bsdf_sample(*bsdf, si.ns, wo, sampler.get_1d(bounce(state.vertex(), sample_dim::kBsdfLobe)),
                                sampler.get_2d(bounce(state.vertex(), sample_dim::kBsdfDirection)));
    if (!bs || bs->weight.is_black()) break;
    // Reject directions the shading normal allows but the geometry does not (light leaks).
    const bool transmits = dot(si.ng, bs->wi) * dot(si.ng, wo) < 0.0f;
    if (transmits && !std::holds_alternative<DielectricBsdf>(*bsdf)) break;
    if (transmits && entry) scratch.stack.cross(*entry);
    state.throughput *= bs->weight;
    state.specular_bounce = bs->specular;
    state.camera_view = state.camera_view && bs->specular;
    if (!bs->specular) state.count_nonspecular_event(false);
    state.scatter_pdf = bs->pdf;
    state.scatter_origin = si.p;
    state.scatter_normal = light_choice_normal(si, wo);
    state.scattered_in_medium = false;
    ray = {offset_ray_origin(si.p, si.ng, bs->wi), bs->wi, 0.0f, kInfinity};
    ++state.surface_bounces;
    state.in_volume_run = false;
    ++state.events;
    if (!russian_roulette(state, sampler, settings)) break;
  }
  if (state.deferred_nee && !scratch.deferred.empty())
    deferred_connections(scene, *state.light_sampler, sampler, settings.deferred_nee, state.vertex() + 1, nested,
                         scratch, counters, out);
  out.alpha = 1.0f - state.visibility;
  return out;
}

}  // namespace caligo
