#include "integrators/path_tracer.h"

#include <algorithm>

#include "core/sampling.h"
#include "integrators/emission_direct.h"
#include "integrators/guided_direction.h"
#include "integrators/interface_eta.h"
#include "integrators/medium_segment.h"
#include "integrators/path_state.h"
#include "integrators/visibility.h"
#include "integrators/volume_direct.h"
#include "lights/light_sample.h"
#include "materials/bsdf.h"

namespace caligo {
namespace {

using sample_dim::bounce;

// The probability that next-event estimation at the previous vertex chose `light`.
float light_choice_pmf(const PathContext& ctx, const PathState& state, int light) {
  if (!state.scattered_in_medium) return ctx.lights.choice_pmf(state.scatter_origin, state.scatter_normal, light);
  return state.light_choice_at_point ? ctx.lights.choice_pmf(state.scatter_origin, Vec3(0.0f), light)
                                     : ctx.lights.choice_pmf_segment(state.scatter_segment, light);
}

float mis_weight_for_hit(const PathContext& ctx, const PathState& state, int light, Vec3 wi, Vec3 p, Vec3 n) {
  if (state.specular_bounce) return 1.0f;
  if (state.deferred_nee && state.scattered_in_medium) return 0.0f;  // deferred connections count it
  const float light_pdf_sa =
      light_choice_pmf(ctx, state, light) * light_pdf(ctx.scene.lights()[size_t(light)], state.scatter_origin, wi, p, n);
  return power_heuristic(1, state.scatter_pdf, 1, light_pdf_sa);
}

// Cycles' camera-ray visibility of the world, extended through specular chains (see
// EnvironmentLight::visible): NEE never reaches those rays, so lighting is unchanged.
bool hidden_from_view(const Light& light, const PathState& state) {
  const auto* env = std::get_if<EnvironmentLight>(&light);
  return env && !env->visible && state.camera_view;
}

RGB emitted(const PathContext& ctx, const PathState& state, const SurfaceInteraction& si, Vec3 wo) {
  if (si.material->emission.is_black()) return RGB(0.0f);
  const bool front = dot(si.ng, wo) > 0.0f || si.material->two_sided_emission;
  if (!front) return RGB(0.0f);
  if (si.light < 0) return si.material->emission;
  return si.material->emission * mis_weight_for_hit(ctx, state, si.light, -wo, si.p, si.ng);
}

// The normal surface light choice uses: light is only taken from the side wo is on (the
// geometric test below), so lights behind the surface get no share.
Vec3 light_choice_normal(const SurfaceInteraction& si, Vec3 wo) { return face_forward(si.ng, wo); }

// Light connection at a surface to one chosen light, one point on it. Its shadow ray is
// secondary (PathSettings::secondary) unless the camera ray found this surface.
RGB connect_surface(const PathContext& ctx, const PathState& state, const SurfaceInteraction& si, Vec3 wo,
                    LightChoice choice) {
  const Sampler& sampler = ctx.sampler;
  const int depth = state.vertex();
  const Light& light = ctx.scene.lights()[size_t(choice.light)];
  const auto ls = sample_light(
      light, si.p, is_delta(light) ? Vec2{0.5f, 0.0f} : sampler.get_2d(bounce(depth, sample_dim::kLightPosition)));
  if (!ls || ls->radiance.is_black() || !(ls->pdf > 0.0f)) return RGB(0.0f);
  const RGB f = bsdf_eval(si.material->bsdf, si.ns, wo, ls->wi) * abs_dot(si.ns, ls->wi);
  if (f.is_black() || dot(si.ng, ls->wi) * dot(si.ng, wo) <= 0.0f) return RGB(0.0f);
  bool through_interface = false;
  const RGB tr = light_transmittance(ctx.scene, offset_ray_origin(si.p, si.ng, ls->wi), si.p, *ls,
                                     ctx.scene.casts_shadows(choice.light),
                                     shadow_medium(ctx, depth, state.events > 0, sample_dim::kLightPosition),
                                     ctx.scratch, ctx.counters, kInfinity, &through_interface);
  if (tr.is_black()) return RGB(0.0f);
  const float light_pdf_sa = choice.pmf * ls->pdf;
  const float weight = ls->delta || through_interface
                           ? 1.0f
                           : power_heuristic(1, light_pdf_sa, 1,
                                             bsdf_sampling_pdf(ctx, si.p, si.material->bsdf, si.ns, wo, ls->wi));
  return f * tr * ls->radiance * (weight / light_pdf_sa);
}

// Light connection at a surface: the lights the light sampler chooses (one, or several where the
// light tree splits), each at one point. Random numbers that would not be used are not drawn
// (one light, a delta light's position).
RGB surface_direct_light(const PathContext& ctx, const PathState& state, const SurfaceInteraction& si, Vec3 wo) {
  const float u = ctx.lights.needs_random() ? ctx.sampler.get_1d(bounce(state.vertex(), sample_dim::kLightSelect)) : 0.0f;
  RGB sum(0.0f);
  for (const LightChoice& choice : ctx.lights.choose(si.p, light_choice_normal(si, wo), u))
    sum += connect_surface(ctx, state, si, wo, choice);
  return sum;
}

// Returns false when the path ends (absorbed or rouletted).
bool russian_roulette(const PathContext& ctx, PathState& state) {
  if (state.events < ctx.settings.russian_roulette_depth) return true;
  const float survive = std::min(1.0f, state.throughput.max_component());
  if (survive >= 1.0f) return true;  // no draw: it could not end the path
  if (ctx.sampler.get_1d(bounce(state.vertex(), sample_dim::kRussianRoulette)) >= survive) return false;
  state.throughput *= 1.0f / survive;
  return true;
}

void record_first_hit(PathSample& out, const SurfaceInteraction& si, float t) {
  out.hit_t = t;
  out.normal = si.ns;
  out.albedo = bsdf_albedo(si.material->bsdf);
}

// Phase 1 with the medium stack: the nearest hit that is seen. Off null surfaces are crossed as
// nearest_non_null_hit does; priority surfaces whose crossing the rules call false are crossed and
// queued in scratch.pending (applied to the stack once the path is known to get past them).
// Returns the first Off non-null surface or real priority crossing, whose crossing is NOT
// applied (a dielectric may reflect).
std::optional<SurfaceHit> nearest_visible_hit(const PathContext& ctx, const Ray& ray) {
  PathScratch& scratch = ctx.scratch;
  scratch.pending.clear();
  scratch.layer_hits.clear();
  scratch.work.assign(scratch.stack);
  Ray probe = ray;
  for (int crossings = 0; crossings <= ctx.settings.max_null_crossings; ++crossings) {
    ++ctx.counters.rays;
    const auto hit = ctx.scene.surfaces().intersect(probe);
    if (!hit) return std::nullopt;
    if (const auto entry = ctx.scene.medium_entry(hit->geom_id)) {
      if (scratch.work.peek(*entry).real) return hit;
      scratch.work.cross(*entry);
      scratch.pending.push_back({hit->t, *entry});
    } else if (ctx.scene.is_transparent(hit->geom_id)) {
      scratch.layer_hits.push_back(*hit);
    } else if (!std::holds_alternative<NullBsdf>(ctx.scene.material(*hit).bsdf)) {
      return hit;
    }
    probe.tmin = hit->t + std::max(1e-4f, hit->t * 1e-5f);
  }
  return std::nullopt;
}

// Phase 1: where the segment ends (the medium stack's rules in nested scenes), with the partly
// transparent surfaces in front of it in scratch.layer_hits.
std::optional<SurfaceHit> segment_end(const PathContext& ctx, const Ray& ray) {
  if (ctx.nested) return nearest_visible_hit(ctx, ray);
  ctx.scratch.layer_hits.clear();
  return nearest_non_null_hit(ctx.scene, ray, ctx.settings.max_null_crossings, &ctx.counters.rays,
                              ctx.scene.has_transparent_surfaces() ? &ctx.scratch.layer_hits : nullptr);
}

// The queued false crossings before t_limit join the path's stack; the queue empties.
void apply_pending(PathScratch& scratch, float t_limit) {
  for (const PendingCrossing& p : scratch.pending)
    if (p.t < t_limit) scratch.stack.cross(p.entry);
  scratch.pending.clear();
}

// Deferred next-event estimation (PathSettings::deferred_nee), the seed's form: once the path is
// built, `count` connections, each to one of its marched segments in media (or scattering vertices
// of tracked segments) chosen with probability q_i proportional to throughput x the segment's
// scatter probability (the integral of sigma_s T; 1 for a vertex) and weighted 1 / (count q_i).
// A segment connects as per-segment NEE does, over its stored record (equiangular and density
// sampling, the light sampler's segment form); a vertex at its point. Without MIS partner: light
// hits by phase-sampled rays from media count zero. Random numbers come from the vertex indices
// after the path's last one.
void deferred_connections(const PathContext& ctx, int first_dim, PathSample& out) {
  PathScratch& scratch = ctx.scratch;
  const int count = ctx.settings.deferred_nee;
  double total = 0.0;
  for (const auto& v : scratch.deferred) total += double(v.weight);
  if (!(total > 0.0)) return;
  for (int k = 0; k < count; ++k) {
    const int dim = first_dim + k;
    // The entry: inverse CDF over the weights.
    const double target = double(ctx.sampler.get_1d(bounce(dim, sample_dim::kFreeFlightChannel))) * total;
    size_t i = 0;
    double acc = double(scratch.deferred[0].weight);
    while (acc <= target && i + 1 < scratch.deferred.size()) acc += double(scratch.deferred[++i].weight);
    const auto& v = scratch.deferred[i];
    const float q = float(double(v.weight) / total);
    if (!(q > 0.0f)) continue;
    if (ctx.nested) {
      scratch.stack.assign(scratch.deferred_stacks[i]);
      scratch.pending.clear();
      if (v.segment >= 0) scratch.pending = scratch.deferred_pending[i];
    }
    RGB light;
    if (v.segment >= 0) {
      const PathScratch::DeferredSegment& seg = scratch.deferred_segments[size_t(v.segment)];
      light = volume_direct_light(ctx, seg.ray, scratch.deferred_records[size_t(v.segment)], dim, seg.secondary);
    } else {
      const auto lobes = std::span<const PhaseLobe>(scratch.deferred_lobes).subspan(v.first_lobe, v.lobe_count);
      light = point_volume_direct_light(ctx, v.x, v.wo, lobes, dim, kInfinity);
    }
    out.add(v.kind, v.beta * light * (1.0f / (float(count) * q)));
  }
}

// Event: the path leaves the scene; what the lights at infinity send along it.
void escape(const PathContext& ctx, const PathState& state, Vec3 w, PathSample& out) {
  RGB sum;
  for (int i : ctx.scene.infinite_lights()) {
    if (hidden_from_view(ctx.scene.lights()[size_t(i)], state)) continue;
    const RGB le = escaped_radiance(ctx.scene.lights()[size_t(i)], w);
    if (!le.is_black()) sum += le * mis_weight_for_hit(ctx, state, i, w, {}, {});
  }
  out.add(state.arriving(LightKind::kBackground), state.throughput * sum);
}

// Event: the path meets a surface that is seen: emission, a light connection, the BSDF sample
// that continues it. False when the path ends there.
bool surface_hit(const PathContext& ctx, PathState& state, Ray& ray, const SurfaceInteraction& si,
                 std::optional<MediumEntry> entry, PathSample& out) {
  const Sampler& sampler = ctx.sampler;
  const Vec3 wo = -ray.direction;
  out.add(state.arriving(LightKind::kSurfaceEmission), state.throughput * emitted(ctx, state, si, wo));
  if (!state.may_bounce(ctx.settings.limits.max_bounces)) return false;
  if (!is_specular(si.material->bsdf)) {
    out.add(state.connected(false), state.throughput * surface_direct_light(ctx, state, si, wo));
    if (ctx.emission)
      out.add(state.connected(false),
              state.throughput * emission_direct_light(ctx, {si.p, wo, {}, &si}, state.vertex()));
  }
  // A dielectric refracts with the IORs of the media actually on either side.
  const Bsdf* bsdf = &si.material->bsdf;
  Bsdf interface;
  if (const auto* d = std::get_if<DielectricBsdf>(bsdf); d && ctx.nested) {
    interface = DielectricBsdf{interface_eta(ctx.scratch.stack, entry, d->ior, dot(si.ng, wo) > 0.0f)};
    bsdf = &interface;
  }
  const DirectionalTree* guide = surface_guide(ctx, si.p, *bsdf);
  const auto bs = guide ? guided_bsdf_sample(ctx, *guide, *bsdf, si.ns, wo, state.vertex())
                        : bsdf_sample(*bsdf, si.ns, wo, sampler.get_1d(bounce(state.vertex(), sample_dim::kBsdfLobe)),
                                      sampler.get_2d(bounce(state.vertex(), sample_dim::kBsdfDirection)));
  if (!bs || bs->weight.is_black()) return false;
  // Reject directions the shading normal allows but the geometry does not (light leaks).
  const bool transmits = dot(si.ng, bs->wi) * dot(si.ng, wo) < 0.0f;
  if (transmits && !std::holds_alternative<DielectricBsdf>(*bsdf)) return false;
  if (transmits && entry) ctx.scratch.stack.cross(*entry);
  const float pdf_native = guide ? bsdf_pdf(*bsdf, si.ns, wo, bs->wi) : bs->pdf;
  if (guide) note_guided_sample(ctx, pdf_native, bs->pdf);
  state.throughput *= bs->weight;
  if (trains_surface(ctx, *bsdf))
    remember_guided_vertex(ctx, si.p, true, bs->wi, bs->weight, bs->pdf, pdf_native, state.throughput, out);
  state.specular_bounce = bs->specular;
  state.camera_view = state.camera_view && bs->specular;
  if (!bs->specular) state.count_nonspecular_event(false);
  state.scatter_pdf = bs->pdf;
  state.emission_weight = bs->specular ? 1.0f : emission_bounce_weight(ctx, si.p, bs->wi, bs->pdf);
  state.scatter_origin = si.p;
  state.scatter_normal = light_choice_normal(si, wo);
  state.scattered_in_medium = false;
  ray = {offset_ray_origin(si.p, si.ng, bs->wi), bs->wi, 0.0f, kInfinity};
  ++state.surface_bounces;
  state.in_volume_run = false;
  ++state.events;
  return russian_roulette(ctx, state);
}

// The first surface the camera ray meets is recorded before the medium in front of it is
// sampled: a camera path that scatters on the way still reports the surface behind. Returns
// the interaction when it was computed (so the surface event need not compute it again).
std::optional<SurfaceInteraction> camera_first_hit(const PathContext& ctx, PathState& state, const Ray& ray,
                                                   const std::optional<SurfaceHit>& hit, PathSample& out) {
  if (!hit || state.events != 0 || state.first_hit_recorded) return std::nullopt;
  std::optional<SurfaceInteraction> si = ctx.scene.interaction(ray, *hit);
  if (!(ctx.nested && ctx.scene.medium_entry(hit->geom_id) && std::holds_alternative<NullBsdf>(si->material->bsdf))) {
    record_first_hit(out, *si, hit->t);
    state.first_hit_recorded = true;
  }
  return si;
}

enum class Next { kContinue, kSurface, kLayer, kStop };

// The camera ray itself (no event yet; null boundaries are not events) sees the background, or a
// holdout, at the end of this segment: its share joins the visibility (1 - alpha) whether or not
// the path then scatters on the way, so alpha behind a medium is exact, not 0 or 1. Glass and
// mirrors are opaque to alpha, as in Arnold and Cycles by default: what is seen in them is part
// of the render, not a hole onto the plate; partly transparent surfaces pass their share (layers of
// the record). The medium segment in front of the hit comes next; on kLayer, *layer is the
// surface of scratch.layer_hits the path meets.
Next medium_in_front(const PathContext& ctx, PathState& state, Ray& ray, const std::optional<SurfaceHit>& hit,
                     bool holdout_hit, PathSample& out, int* layer) {
  const bool camera_ray = state.events == 0;
  if (!ctx.has_volumes && ctx.scratch.layer_hits.empty()) {
    if (camera_ray && (!hit || holdout_hit)) state.visibility += state.throughput.average();
    return Next::kSurface;
  }
  const RGB throughput_in = state.throughput;  // the segment changes it
  SegmentEvent event;
  const size_t deferred_before = ctx.scratch.deferred.size();
  const SegmentOutcome outcome = medium_segment(ctx, state, ray, hit ? hit->t : kInfinity,
                                                ctx.nested ? ctx.scratch.stack.current().medium : -1, out, &event);
  if (camera_ray) {
    // The throughput carries earlier segments' (coloured) transmittance: the channel average
    // of the product, not the product of averages.
    const TransmittanceRecord& record = ctx.scratch.record;
    if (!hit || holdout_hit) state.visibility += (throughput_in * record.transmittance_end()).average();
    state.visibility += throughput_in.average() * record.holdout_total();
  }
  if (outcome == SegmentOutcome::kAbsorbed) return Next::kStop;
  if (outcome == SegmentOutcome::kPassed) return Next::kSurface;
  PathScratch& scratch = ctx.scratch;
  if (ctx.nested) apply_pending(scratch, event.t);
  if (outcome == SegmentOutcome::kLayer) {
    *layer = event.layer;
    return Next::kLayer;
  }
  // A tracked event's deferred vertex takes the stack after its false crossings (a marched
  // segment's entry kept the stack at its start, with the crossings).
  if (ctx.nested && state.deferred_nee && scratch.deferred.size() > deferred_before &&
      scratch.deferred.back().segment < 0) {
    if (scratch.deferred_stacks.size() < scratch.deferred.size()) scratch.deferred_stacks.resize(scratch.deferred.size());
    scratch.deferred_stacks[scratch.deferred.size() - 1].assign(scratch.stack);
  }
  ++state.events;
  return russian_roulette(ctx, state) ? Next::kContinue : Next::kStop;
}

}  // namespace

PathSample trace_path(const Scene& scene, Ray ray, const Sampler& sampler, const PathSettings& settings,
                      PathCounters& counters, PathScratch& scratch, PathGuiding guiding) {
  // Scenes without priority surfaces take exactly the paths they took before nested media.
  const EmissionSampler* emission =
      settings.sample_emission && !scene.emission_sampler().empty() ? &scene.emission_sampler() : nullptr;
  PathContext ctx{scene,    sampler, settings, scratch, counters, scene.light_sampler(settings.light_sampler),
                        scene.has_priority_objects(), !scene.volumes().empty() || scene.volumes().has_media(),
                        emission};
  // Deferred connections have no single incident direction for a vertex to learn from.
  if (guiding.field && settings.deferred_nee <= 0 && settings.guiding != GuidingMode::kOff) {
    ctx.guide = guiding.field;
    ctx.guide_surfaces = settings.guiding == GuidingMode::kSurface || settings.guiding == GuidingMode::kAll;
    ctx.guide_volumes = settings.guiding == GuidingMode::kVolume || settings.guiding == GuidingMode::kAll;
    ctx.train = guiding.train;
  }
  scratch.guided.clear();
  scratch.guided_growth = 1.0f;
  PathSample out;
  PathState state;
  state.deferred_nee = settings.deferred_nee > 0;
  scratch.deferred.clear();
  scratch.deferred_lobes.clear();
  scratch.deferred_segments.clear();
  if (ctx.nested) {
    scratch.stack.assign(scene.camera_stack());
    scratch.pending.clear();
  }
  for (;;) {
    // A degenerate computation upstream (a NaN direction or weight) ends the path here
    // rather than poisoning the pixel; the film drops non-finite samples too.
    if (!is_finite(ray.direction) || !state.throughput.is_finite()) break;
    const auto hit = segment_end(ctx, ray);
    const bool holdout_hit = hit && scene.is_holdout(hit->geom_id);
    const bool camera_ray = state.events == 0;
    const std::optional<SurfaceInteraction> hit_si = camera_first_hit(ctx, state, ray, hit, out);
    int layer = -1;
    const Next next = medium_in_front(ctx, state, ray, hit, holdout_hit, out, &layer);
    if (next == Next::kStop) break;
    if (next == Next::kContinue) continue;
    if (next == Next::kLayer) {
      // A partly transparent surface (its share of the path was chosen in the record's fates).
      const SurfaceInteraction si = scene.interaction(ray, scratch.layer_hits[size_t(layer)]);
      if (!surface_hit(ctx, state, ray, si, std::nullopt, out)) break;
      continue;
    }
    if (ctx.nested) apply_pending(scratch, kInfinity);
    if (!hit) {
      escape(ctx, state, ray.direction, out);
      break;
    }
    // A holdout seen by the camera is a hole in the image (counted in the visibility above);
    // other paths see it as the surface it is (it still shadows and shows in reflections).
    if (holdout_hit && camera_ray) break;
    const SurfaceInteraction si = hit_si ? *hit_si : scene.interaction(ray, *hit);
    const std::optional<MediumEntry> entry = ctx.nested ? scene.medium_entry(hit->geom_id) : std::nullopt;
    if (entry && std::holds_alternative<NullBsdf>(si.material->bsdf)) {
      // A medium boundary the rules make real: the ray's medium changes, nothing is seen.
      scratch.stack.cross(*entry);
      if (++state.boundary_crossings > settings.max_null_crossings) break;
      ray = {offset_ray_origin(si.p, si.ng, ray.direction), ray.direction, 0.0f, kInfinity};
      continue;
    }
    if (!surface_hit(ctx, state, ray, si, entry, out)) break;
  }
  if (state.deferred_nee && !scratch.deferred.empty()) deferred_connections(ctx, state.vertex() + 1, out);
  if (!scratch.guided.empty()) train_guide(ctx, out);
  out.alpha = 1.0f - state.visibility;
  return out;
}

}  // namespace caligo
