#include "tracking/tracking.h"

#include <algorithm>
#include <cmath>

namespace caligo {
namespace {

RGB abs_rgb(RGB v) { return {std::abs(v.r), std::abs(v.g), std::abs(v.b)}; }

// The distance to the next tentative collision of a homogeneous Poisson process of rate mu.
float exponential_step(float mu, Pcg32& rng) { return -std::log1p(-rng.next_float()) / mu; }

// Russian roulette on a running weight that started at 1: false when it ends the walk; the
// survivors are scaled up to the threshold.
bool survive_roulette(RGB& weight, Pcg32& rng) {
  const float m = weight.max_component();
  if (m >= kTrackingRouletteThreshold) return true;
  const float p = m / kTrackingRouletteThreshold;
  if (!(p > 0.0f) || rng.next_float() >= p) return false;
  weight *= 1.0f / p;
  return true;
}

// Calls collision(t, span, mu) for every tentative collision of the collected spans, front to
// back, where mu is the span's scalar majorant per unit t less its `control(span)` (also per unit
// t: the walk samples the residual); stops when it returns false. Returns false when the walk was
// stopped (by the callback or the collision guard).
template <typename ControlFn, typename CollisionFn>
bool for_each_tentative_collision(const MarchScratch& scratch, float dir_length, Pcg32& rng, ControlFn&& control,
                                  CollisionFn&& collision) {
  uint32_t count = 0;
  for (const Span& span : scratch.spans) {
    const float mu = (span.sigma_maj * dir_length - control(span)).max_component();
    if (!(mu > 0.0f)) continue;
    for (float t = span.t0 + exponential_step(mu, rng); t < span.t1; t += exponential_step(mu, rng)) {
      if (++count > kMaxTrackingCollisions) return false;
      if (!collision(t, span, mu)) return false;
    }
  }
  return true;
}

std::span<const uint32_t> span_primitives(const MarchScratch& scratch, const Span& span) {
  return {scratch.span_primitives.data() + span.first, span.count};
}

RGB no_control(const Span&) { return RGB(0.0f); }

}  // namespace

TrackedSegment track_free_flight(const VolumeScene& volumes, const Ray& ray, RGB throughput, bool may_scatter,
                                 bool gather_emission, MarchScratch& scratch, Pcg32& rng, RGB weight) {
  TrackedSegment out;
  out.weight = weight;
  const float dir_length = length(ray.direction);
  bool done = false;
  const bool walked = for_each_tentative_collision(
      scratch, dir_length, rng, no_control, [&](float t, const Span& span, float mu) {
        const std::span<const uint32_t> prims = span_primitives(scratch, span);
        ++out.collisions;
        ++scratch.steps;
        scratch.shader_evaluations += prims.size();
        const StepCoefficients c =
            shade_span(volumes, prims, ray.at(t), dir_length, scratch.volume, may_scatter ? &scratch.lobes : nullptr);
        if (gather_emission && !c.emission.is_black()) out.emission += out.weight * c.emission * (1.0f / mu);
        const RGB sigma_n = RGB(mu) - c.sigma_t;
        // History-aware probabilities (Kutz et al. 2017, eq. 29 without the absorption event).
        const RGB history = abs_rgb(throughput * out.weight);
        const float ps = may_scatter ? (c.sigma_s * history).max_component() : 0.0f;
        const float pn = (abs_rgb(sigma_n) * history).max_component();
        const float total = ps + pn;
        if (!(total > 0.0f)) {  // nothing scatters and the majorant is met: all absorbed
          out.weight = RGB(0.0f);
          done = true;
          return false;
        }
        if (rng.next_float() * total < ps) {
          out.weight *= c.sigma_s * (total / (mu * ps));
          out.outcome = TrackedSegment::Outcome::kScattered;
          out.t = t;
          out.sigma_s = c.sigma_s;
          done = true;
          return false;
        }
        out.weight *= sigma_n * (total / (mu * pn));
        if (!survive_roulette(out.weight, rng)) {
          out.weight = RGB(0.0f);
          done = true;
          return false;
        }
        return true;
      });
  if (!walked && !done) out.weight = RGB(0.0f);  // the collision guard: opaque
  if (out.outcome != TrackedSegment::Outcome::kScattered && out.weight.is_black())
    out.outcome = TrackedSegment::Outcome::kAbsorbed;
  return out;
}

namespace {

// Calls walk(chunk) for consecutive chunks of `ray` within the extent of its coarse spans (in
// scratch on entry), with the chunk's fine spans collected into scratch; stops when it returns
// false. A chunk's length aims at kTrackingChunkDepth of majorant optical depth: the first from
// the coarse bound, each next from the depth the last one had (at most 8x longer each time).
template <typename WalkFn>
void for_each_chunk(const VolumeScene& volumes, const Ray& ray, const MarchSettings& settings, int medium,
                    MarchScratch& scratch, WalkFn&& walk) {
  if (scratch.spans.empty()) return;
  const float dir_length = length(ray.direction);
  const float start = std::max(ray.tmin, scratch.spans.front().t0), end = std::min(ray.tmax, scratch.spans.back().t1);
  float sigma = 0.0f;
  for (const Span& s : scratch.spans) sigma = std::max(sigma, s.sigma_maj.max_component() * dir_length);
  if (!(sigma > 0.0f) || !(start < end)) return;
  float length_t = kTrackingChunkDepth / sigma;
  for (float t = start; t < end;) {
    Ray chunk = ray;
    chunk.tmin = t;
    chunk.tmax = end - t > length_t ? t + length_t : end;
    if (!(chunk.tmax > t)) chunk.tmax = end;  // a length lost to rounding at large t
    t = chunk.tmax;
    if (!collect_spans(volumes, chunk, settings, scratch, medium)) {
      length_t *= 8.0f;
      continue;
    }
    float depth = 0.0f;
    for (const Span& s : scratch.spans) depth += s.sigma_maj.max_component() * dir_length * (s.t1 - s.t0);
    length_t *= depth > kTrackingChunkDepth / 8.0f ? kTrackingChunkDepth / depth : 8.0f;
    if (!walk(chunk)) return;
  }
}

}  // namespace

TrackedSegment track_free_flight_chunked(const VolumeScene& volumes, const Ray& ray, const MarchSettings& settings,
                                         int medium, RGB throughput, bool may_scatter, bool gather_emission,
                                         MarchScratch& scratch, Pcg32& rng) {
  TrackedSegment total;
  for_each_chunk(volumes, ray, settings, medium, scratch, [&](const Ray& chunk) {
    TrackedSegment seg =
        track_free_flight(volumes, chunk, throughput, may_scatter, gather_emission, scratch, rng, total.weight);
    seg.emission += total.emission;
    seg.collisions += total.collisions;
    total = seg;
    return total.outcome == TrackedSegment::Outcome::kPassed;
  });
  return total;
}

RGB track_transmittance(const VolumeScene& volumes, const Ray& ray, const MarchSettings& settings,
                        MarchScratch& scratch, Pcg32& rng, int medium, bool residual) {
  if (!collect_coarse_spans(volumes, ray, settings, scratch, medium)) return RGB(1.0f);
  return track_transmittance_chunked(volumes, ray, settings, medium, scratch, rng, residual);
}

RGB track_transmittance_chunked(const VolumeScene& volumes, const Ray& ray, const MarchSettings& settings, int medium,
                                MarchScratch& scratch, Pcg32& rng, bool residual) {
  RGB tr(1.0f);
  for_each_chunk(volumes, ray, settings, medium, scratch, [&](const Ray& chunk) {
    tr = track_transmittance_collected(volumes, chunk, scratch, rng, residual, tr);
    // Roulette between chunks too: the control alone (constant blocks, no collision) can take
    // the weight far below the threshold, and the walk would then go on to the ray's end.
    if (!tr.is_black() && !survive_roulette(tr, rng)) tr = RGB(0.0f);
    return !tr.is_black();
  });
  return tr;
}

RGB track_transmittance_collected(const VolumeScene& volumes, const Ray& ray, MarchScratch& scratch, Pcg32& rng,
                                  bool residual, RGB weight) {
  const float dir_length = length(ray.direction);
  // The control per unit t, never above the majorant (which rounding could otherwise cross).
  const auto control = [&](const Span& span) {
    return residual ? RGB(std::min(span.sigma_min.r, span.sigma_maj.r), std::min(span.sigma_min.g, span.sigma_maj.g),
                          std::min(span.sigma_min.b, span.sigma_maj.b)) *
                          dir_length
                    : RGB(0.0f);
  };
  RGB control_depth;
  for (const Span& span : scratch.spans) control_depth += control(span) * (span.t1 - span.t0);
  RGB tr = weight * exp_neg(control_depth);
  const bool walked = for_each_tentative_collision(
      scratch, dir_length, rng, control, [&](float t, const Span& span, float mu_r) {
        const std::span<const uint32_t> prims = span_primitives(scratch, span);
        ++scratch.steps;
        scratch.shader_evaluations += prims.size();
        const StepCoefficients c = shade_span(volumes, prims, ray.at(t), dir_length, scratch.volume, nullptr);
        tr *= (RGB(mu_r) - (c.sigma_t - control(span))) * (1.0f / mu_r);
        return survive_roulette(tr, rng);
      });
  return walked ? tr : RGB(0.0f);
}

}  // namespace caligo
