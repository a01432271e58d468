// The medium events of a path (path_tracer.cpp's phases 2 and 3): a segment marched into a
// TransmittanceRecord or tracked, its light connection, and scattering by the phase mixture.
#include "integrators/medium_segment.h"

#include <algorithm>
#include <cmath>

#include "integrators/emission_direct.h"
#include "integrators/guided_direction.h"
#include "integrators/guided_distance.h"
#include "integrators/visibility.h"
#include "integrators/volume_direct.h"
#include "tracking/tracking.h"

namespace caligo {
namespace {

using sample_dim::bounce;

// Whether the path may scatter in a medium now: max_volume_bounces bounds the events, and a path
// that has used up its bounces may not start another run (a scattering event after the last
// surface bounce would lengthen it).
bool may_scatter_in_medium(const PathContext& ctx, const PathState& state) {
  return state.volume_bounces < ctx.settings.limits.max_volume_bounces &&
         (state.in_volume_run || state.may_bounce(ctx.settings.limits.max_bounces));
}

// Event: the path scatters in a medium at x, `t` along `ray` (whose segment the light choice of
// a marched event covers), with the phase mixture `lobes`; the phase sample gives the next ray.
// Emissive grids are connected to here, whatever the segment's estimator.
SegmentOutcome scatter_in_medium(const PathContext& ctx, PathState& state, Ray& ray, float t,
                                 std::span<const PhaseLobe> lobes, const Ray* marched_segment, PathSample& out) {
  const Vec3 x = ray.at(t);
  const Sampler& sampler = ctx.sampler;
  const RGB beta = state.throughput;  // at the vertex, before the phase sample (deferred NEE)
  const DirectionalTree* guide = volume_guide(ctx, x);
  const MixedPhaseSample ps =
      guide ? guided_phase_sample(ctx, *guide, lobes, ray.direction, state.vertex())
            : sample_mixed_phase(lobes, ray.direction,
                                 lobes.size() > 1 ? sampler.get_1d(bounce(state.vertex(), sample_dim::kPhaseLobe)) : 0.0f,
                                 sampler.get_2d(bounce(state.vertex(), sample_dim::kPhaseDirection)));
  if (ctx.emission)
    out.add(state.connected(true), beta * emission_direct_light(ctx, {x, ray.direction, lobes}, state.vertex()));
  const float pdf_native = guide ? mixed_phase_pdf(lobes, ray.direction, ps.wi) : ps.pdf;
  if (guide) note_guided_sample(ctx, pdf_native, ps.pdf);
  state.throughput *= ps.weight;
  if (state.throughput.is_black()) return SegmentOutcome::kAbsorbed;
  if (trains_volume(ctx))
    remember_guided_vertex(ctx, x, false, ps.wi, ps.weight, ps.pdf, pdf_native, state.throughput, out);
  state.emission_weight = emission_bounce_weight(ctx, x, ps.wi, ps.pdf);
  // Kept only on the scattered outcome, which is where trace_path stores its medium stack.
  PathScratch& scratch = ctx.scratch;
  if (ctx.settings.deferred_nee > 0 && !marched_segment) {  // a marched segment is deferred whole
    scratch.deferred.push_back({x, ray.direction, beta, state.connected(true), uint32_t(scratch.deferred_lobes.size()),
                                uint32_t(lobes.size()), -1, beta.average()});
    scratch.deferred_lobes.insert(scratch.deferred_lobes.end(), lobes.begin(), lobes.end());
  }
  state.specular_bounce = false;
  state.camera_view = false;
  state.scatter_pdf = ps.pdf;
  state.scatter_origin = x;
  state.scattered_in_medium = true;
  state.light_choice_at_point = marched_segment == nullptr;
  if (marched_segment) state.scatter_segment = *marched_segment;
  state.count_nonspecular_event(true);
  ray = {x, ps.wi, 0.0f, kInfinity};
  ++state.volume_bounces;
  if (!state.in_volume_run) ++state.volume_runs;
  state.in_volume_run = true;
  return SegmentOutcome::kScattered;
}

// Event: light connection from a marched segment (the seed's next-event estimation along the
// record). Segments that barely scatter (thin fog between two walls) contribute little
// in-scattered light but cost two shadow rays: the connection runs with a probability that
// follows the segment's scattering probability, and is reweighted (unbiased roulette).
void connect_marched_segment(const PathContext& ctx, const PathState& state, const Ray& ray,
                             const TransmittanceRecord& record, PathSample& out) {
  const float nee_probability = std::min(1.0f, ctx.settings.volume_nee_scale * record.scatter_weight_total());
  const float u = nee_probability < 1.0f
                      ? ctx.sampler.get_1d(bounce(state.vertex(), sample_dim::kVolumeNeeRoulette))
                      : 0.0f;
  if (nee_probability > 0.0f && u < nee_probability)
    out.add(state.connected(true),
            state.throughput * volume_direct_light(ctx, ray, record, state.vertex(), state.events > 0) /
                nee_probability);
}

// The fate of a path in a chromatic record by hero-channel spectral MIS over the whole path
// (Wilkie et al. 2014, "Hero Wavelength Spectral Sampling"): the path draws one hero channel at
// its first chromatic segment, and every chromatic segment samples its fate in that channel's
// own proportion S_h : P_h (scatter at density sigma_s,h T_h, or pass). The path's pdf in channel
// k is the product of the same fates' pdfs in channel k (state.channel_pdf, kept normalised);
// each channel is weighted by the balance heuristic over the three, f_k / avg_k' pdf_k'(path),
// so in an albedo-1 medium no channel's weight exceeds 3. Choosing fates by the channel average
// instead made the densest channel of an albedo-1 furnace 6-8x noisier than the others, with
// fireflies that kept its mean from converging. Surface layers are a fourth fate, met with
// density opacity x T_h in front. Returns the collision (or layer) with its pdf set so that the
// caller's sigma_s T / pdf (opacity T / pdf) is the balance-heuristic weight, or std::nullopt
// with *pass_weight the factor on the throughput of passing (0: absorbed).
std::optional<DistanceSample> chromatic_fate(const TransmittanceRecord& record, PathState& state, bool may_scatter,
                                             float u_channel, float u, RGB* pass_weight) {
  const RGB scatter = may_scatter ? record.scatter_totals() : RGB(0.0f), pass = record.transmittance_end();
  const RGB layers = record.layer_totals();
  const RGB survive = scatter + layers + pass;
  *pass_weight = RGB(0.0f);
  if (state.hero_channel < 0) state.hero_channel = std::min(int(u_channel * 3.0f), 2);
  const int h = state.hero_channel;
  if (!(survive[h] > 0.0f)) return std::nullopt;  // the hero channel is absorbed: so is the path
  // fate_pdf[k]: the fate's pdf in channel k; the weight divides by the path's mixture pdf.
  const auto advance = [&](RGB fate_pdf) {
    const float before = state.channel_pdf.average();
    state.channel_pdf *= fate_pdf;
    const float after = state.channel_pdf.average();
    if (!(after > 0.0f)) return 0.0f;
    state.channel_pdf *= 1.0f / after;  // ratios matter only; this keeps them finite
    return after / before;              // the mixture pdf of this fate, relative to the path so far
  };
  const auto per_channel = [&](RGB f) {
    return RGB(survive.r > 0.0f ? f.r / survive.r : 0.0f, survive.g > 0.0f ? f.g / survive.g : 0.0f,
               survive.b > 0.0f ? f.b / survive.b : 0.0f);
  };
  const float p_scatter = scatter[h] / survive[h];
  if (u < p_scatter) {
    auto collision = record.sample_scatter_channel(h, u / p_scatter);
    if (!collision) return std::nullopt;  // rounding left no mass: treated as absorbed
    const MarchStep& step = record.steps()[size_t(collision->step)];
    collision->pdf = advance(per_channel(step.sigma_s * record.transmittance(collision->t)));
    if (collision->pdf > 0.0f) return collision;
    return std::nullopt;
  }
  const float p_layer = layers[h] / survive[h];
  if (u < p_scatter + p_layer) {
    auto layer = record.sample_layer(h, std::min((u - p_scatter) / p_layer, kOneMinusEpsilon));
    if (!layer) return std::nullopt;
    const SurfaceLayer& l = record.layers()[size_t(layer->layer)];
    layer->pdf = advance(per_channel(l.before * l.opacity));
    if (layer->pdf > 0.0f) return layer;
    return std::nullopt;
  }
  const float p_pass = advance(per_channel(pass));
  if (p_pass > 0.0f) *pass_weight = pass / p_pass;
  return std::nullopt;
}

// Where a grey segment's scattering event lies: by the record's density, or by its mixture
// with the learnt fluence (integrators/guided_distance.h). Not counted in the path's guided
// growth: the segment's light connection has already read it, and the vertex's own MIS weights
// must read what it read.
std::optional<DistanceSample> scatter_distance(const PathContext& ctx, const Ray& ray, const TransmittanceRecord& record,
                                               float u_channel, float u) {
  if (ctx.settings.guided_distances && volume_guides_distances(ctx))
    if (const auto guided = GuidedDistance::along(*ctx.guide, ray, record)) return guided->sample(record, u, nullptr);
  return record.sample_scatter_density(u_channel, u);
}

// Event: a marched medium segment (phases 2 and 3 of the seed) over the spans already collected.
// Absorption by weight, not by chance (PathSettings::absorption_by_weight; implicit capture): of
// the three fates of a path in the segment -- scatter (probability S = avg_c of the integral of
// sigma_s,c T_c), pass (P = avg_c T_c at the end) or be absorbed (the rest) -- only the first two
// are sampled, in proportion S : P, and both carry the surviving fraction S + P as weight. A
// collision is drawn with density proportional to avg_c sigma_s,c T_c (the sampler light
// connections use); passing carries the record's exact T. A purely absorbing medium (S = 0) has
// zero variance; albedo 1 (S + P = 1) is exactly free-flight sampling. Sampling pass against S
// alone (pass weight T / (1 - S)) was worse in dense, bright media: its passes carry tiny weights
// that Russian roulette then turns into noise (3x the standard error on `sss`). A path that may
// not scatter again just takes T.
// Deferred next-event estimation by segments: the segment joins the path's list with a copy of
// its record, chosen later with probability proportional to throughput x scatter probability.
void defer_segment(const PathContext& ctx, const PathState& state, const Ray& ray, const TransmittanceRecord& record) {
  const float weight = state.throughput.average() * record.scatter_weight_total();
  if (!(weight > 0.0f)) return;
  PathScratch& scratch = ctx.scratch;
  const int segment = int(scratch.deferred_segments.size());
  scratch.deferred_segments.push_back({ray, state.events > 0});
  if (scratch.deferred_records.size() <= size_t(segment)) scratch.deferred_records.resize(size_t(segment) + 1);
  scratch.deferred_records[size_t(segment)] = record;
  scratch.deferred.push_back({{}, ray.direction, state.throughput, state.connected(true), 0, 0, segment, weight});
  if (ctx.nested) {
    const size_t entry = scratch.deferred.size() - 1;
    if (scratch.deferred_stacks.size() <= entry) scratch.deferred_stacks.resize(entry + 1);
    if (scratch.deferred_pending.size() <= entry) scratch.deferred_pending.resize(entry + 1);
    scratch.deferred_stacks[entry].assign(scratch.stack);
    scratch.deferred_pending[entry] = scratch.pending;
  }
}

// The partly transparent surfaces in front of the segment's end as layers of the record.
void record_layers(const PathContext& ctx, TransmittanceRecord& record) {
  PathScratch& scratch = ctx.scratch;
  if (scratch.layer_hits.empty()) return;
  scratch.layers.clear();
  for (const SurfaceHit& h : scratch.layer_hits) scratch.layers.push_back({h.t, ctx.scene.opacity(h), RGB(0.0f)});
  record.insert_layers(scratch.layers);
}

// The fate of a path in a grey record (absorption by weight): scatter, meet a layer or pass, in
// proportion S : H : P, each carrying S + H + P. Returns the collision or layer (its pdf the density
// of the choice), or std::nullopt with the throughput already weighted for passing.
std::optional<DistanceSample> grey_fate(const PathContext& ctx, PathState& state, const Ray& ray,
                                        const TransmittanceRecord& record, bool may_scatter, float u_channel, float u) {
  const RGB t_end = record.transmittance_end();
  const float scatter = may_scatter ? record.scatter_weight_total() : 0.0f;
  const float layers = record.layer_totals().average(), pass = t_end.average();
  const float survive = scatter + layers + pass;
  const float p_scatter = survive > 0.0f ? scatter / survive : 0.0f;
  const float p_layer = survive > 0.0f ? layers / survive : 0.0f;
  if (u < p_scatter) {
    auto collision = scatter_distance(ctx, ray, record, u_channel, u / p_scatter);
    // The collision's density is p_scatter x pdf = avg_c sigma_s,c(t) T_c(t) / survive.
    if (collision) collision->pdf *= p_scatter;
    else state.throughput = RGB(0.0f);  // p_scatter > 0 implies a collision
    return collision;
  }
  if (u < p_scatter + p_layer) {
    auto layer = record.sample_layer(-1, std::min((u - p_scatter) / p_layer, kOneMinusEpsilon));
    if (layer) layer->pdf *= p_layer;
    else state.throughput = RGB(0.0f);
    return layer;
  }
  state.throughput *= pass > 0.0f ? t_end * (survive / pass) : RGB(0.0f);
  return std::nullopt;
}

// The path's fate over a filled record (the absorption-by-weight fates or free flight); returns
// the collision or layer, or std::nullopt when it passed (throughput weighted) or was absorbed
// (throughput black).
std::optional<DistanceSample> segment_fate(const PathContext& ctx, PathState& state, const Ray& ray,
                                           const TransmittanceRecord& record, bool may_scatter) {
  const Sampler& sampler = ctx.sampler;
  const float u = sampler.get_1d(bounce(state.vertex(), sample_dim::kFreeFlightDistance));
  // A grey record samples the same distance whichever channel is picked.
  const float u_channel =
      record.grey() ? 0.0f : sampler.get_1d(bounce(state.vertex(), sample_dim::kFreeFlightChannel));
  if (ctx.settings.absorption_by_weight && !record.grey()) {
    RGB pass_weight;
    auto collision = chromatic_fate(record, state, may_scatter, u_channel, u, &pass_weight);
    if (!collision) state.throughput *= pass_weight;
    return collision;
  }
  if (ctx.settings.absorption_by_weight) return grey_fate(ctx, state, ray, record, may_scatter, u_channel, u);
  auto collision = record.sample_free_flight(u_channel, u);
  if (!collision) {
    const RGB t_end = record.transmittance_end();
    state.throughput *= t_end / t_end.average();
  } else if (!may_scatter && collision->layer < 0) {
    state.throughput = RGB(0.0f);
    return std::nullopt;
  }
  return collision;
}

// Event: a marched medium segment (phases 2 and 3 of the seed) over the spans already collected,
// with the partly transparent surfaces on the way as layers of the record.
// Absorption by weight, not by chance (PathSettings::absorption_by_weight; implicit capture): of
// the three fates of a path in the segment -- scatter (probability S = avg_c of the integral of
// sigma_s,c T_c), pass (P = avg_c T_c at the end) or be absorbed (the rest) -- only the first two
// are sampled, in proportion S : P, and both carry the surviving fraction S + P as weight (layers
// add a fate H, the probability of meeting one). A
// collision is drawn with density proportional to avg_c sigma_s,c T_c (the sampler light
// connections use); passing carries the record's exact T. A purely absorbing medium (S = 0) has
// zero variance; albedo 1 (S + P = 1) is exactly free-flight sampling. Sampling pass against S
// alone (pass weight T / (1 - S)) was worse in dense, bright media: its passes carry tiny weights
// that Russian roulette then turns into noise (3x the standard error on `sss`). A path that may
// not scatter again just takes T.
SegmentOutcome marched_segment(const PathContext& ctx, PathState& state, Ray& ray, float t_surface,
                               PathSample& out, SegmentEvent* event) {
  TransmittanceRecord& record = ctx.scratch.record;
  Ray segment = ray;
  segment.tmax = t_surface;
  march_collected(ctx.scene.volumes(), segment, march_jitter(ctx.scene, ctx.sampler, state.vertex()),
                  ctx.scratch.march_settings, ctx.scratch.march, record);
  record_layers(ctx, record);
  if (record.empty()) return SegmentOutcome::kPassed;
  if (state.events == 0) ctx.counters.camera_march_steps += record.steps().size();
  out.add(state.arriving(LightKind::kVolumeEmission), state.throughput * record.emission() * state.emission_weight);
  const bool may_scatter = may_scatter_in_medium(ctx, state);
  if (may_scatter && ctx.settings.deferred_nee <= 0) connect_marched_segment(ctx, state, ray, record, out);
  if (may_scatter && ctx.settings.deferred_nee > 0) defer_segment(ctx, state, ray, record);
  const std::optional<DistanceSample> collision = segment_fate(ctx, state, ray, record, may_scatter);
  if (!collision) return state.throughput.is_black() ? SegmentOutcome::kAbsorbed : SegmentOutcome::kPassed;
  if (collision->layer >= 0) {
    const SurfaceLayer& l = record.layers()[size_t(collision->layer)];
    state.throughput *= l.before * (l.opacity / collision->pdf);
    *event = {l.t, collision->layer};
    return state.throughput.is_black() ? SegmentOutcome::kAbsorbed : SegmentOutcome::kLayer;
  }
  const MarchStep& step = record.steps()[size_t(collision->step)];
  state.throughput *= step.sigma_s * record.transmittance(collision->t) / collision->pdf;
  if (state.throughput.is_black()) return SegmentOutcome::kAbsorbed;
  event->t = collision->t;
  const Ray choice_segment = light_choice_segment(ray, record);
  return scatter_in_medium(ctx, state, ray, collision->t, record.lobes(step), &choice_segment, out);
}

// Event: a tracked medium segment (tracking/tracking.h) over its coarse spans, already collected:
// spectral tracking to the next scattering event, emission gathered on the way, then a light
// connection at the event itself (the light sampler's point form), as the reference ladder and
// most production renderers connect.
SegmentOutcome tracked_segment(const PathContext& ctx, PathState& state, Ray& ray, float t_surface, int medium,
                               PathSample& out, SegmentEvent* event) {
  ctx.scratch.record.clear();  // no record: nothing may read a stale one
  const bool may_scatter = may_scatter_in_medium(ctx, state);
  Pcg32 rng(ctx.sampler.stream_key(bounce(state.vertex(), sample_dim::kFreeFlightDistance)), 0);
  Ray segment = ray;
  segment.tmax = t_surface;
  const TrackedSegment seg = track_free_flight_chunked(ctx.scene.volumes(), segment, ctx.scratch.march_settings, medium,
                                                       state.throughput, may_scatter, true, ctx.scratch.march, rng);
  if (!seg.emission.is_black())
    out.add(state.arriving(LightKind::kVolumeEmission), state.throughput * seg.emission * state.emission_weight);
  state.throughput *= seg.weight;
  if (seg.outcome == TrackedSegment::Outcome::kAbsorbed || state.throughput.is_black())
    return SegmentOutcome::kAbsorbed;
  if (seg.outcome == TrackedSegment::Outcome::kPassed) return SegmentOutcome::kPassed;
  const Vec3 x = ray.at(seg.t);
  event->t = seg.t;
  // The lobes stay in scratch.march.lobes: shadow rays shade without lobes.
  const std::span<const PhaseLobe> lobes(ctx.scratch.march.lobes);
  if (ctx.settings.deferred_nee <= 0)
    out.add(state.connected(true), state.throughput * point_volume_direct_light(ctx, x, ray.direction, lobes,
                                                                                state.vertex(), seg.t));
  return scatter_in_medium(ctx, state, ray, seg.t, lobes, nullptr, out);
}

}  // namespace

float march_jitter(const Scene& scene, const Sampler& sampler, int depth) {
  return scene.volumes().all_homogeneous() ? 0.5f : sampler.get_1d(bounce(depth, sample_dim::kMarchJitter));
}

// Phases 2 and 3 for the medium in front of the next surface (or to infinity), marched or
// tracked by PathSettings::secondary. `medium`: the scene medium the stack puts the segment in
// (-1: none). On kScattered, *event_t is the event's distance along the old ray.
SegmentOutcome medium_segment(const PathContext& ctx, PathState& state, Ray& ray, float t_surface, int medium,
                              PathSample& out, SegmentEvent* event) {
  Ray segment = ray;
  segment.tmax = t_surface;
  const VolumeScene& volumes = ctx.scene.volumes();
  MarchScratch& scratch = ctx.scratch.march;
  const SecondarySegments policy = ctx.settings.secondary;
  // Layers need the record: a segment with partly transparent surfaces is marched.
  const bool layers = !ctx.scratch.layer_hits.empty();
  // After the first event the coarse spans decide (homogeneous ones are the fine spans too, and a
  // tracked segment collects its fine spans chunk by chunk); the camera segment is marched.
  const bool coarse = state.events > 0 && policy != SecondarySegments::kMarch && !layers;
  const bool any = coarse ? collect_coarse_spans(volumes, segment, ctx.scratch.march_settings, scratch, medium)
                          : collect_spans(volumes, segment, ctx.scratch.march_settings, scratch, medium);
  if (!any && !layers) {
    ctx.scratch.record.clear();
    return SegmentOutcome::kPassed;
  }
  const bool homogeneous = collected_spans_homogeneous(scratch);
  const bool track = coarse && (policy == SecondarySegments::kTrack ||
                                (!homogeneous && !collected_spans_emissive(volumes, scratch)));
  if (track) return tracked_segment(ctx, state, ray, t_surface, medium, out, event);
  if (coarse && !homogeneous &&
      !collect_spans(volumes, segment, ctx.scratch.march_settings, scratch, medium)) {
    ctx.scratch.record.clear();
    return SegmentOutcome::kPassed;
  }
  return marched_segment(ctx, state, ray, t_surface, out, event);
}

}  // namespace caligo
