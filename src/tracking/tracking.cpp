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

// Calls collision(t, primitives, mu) for every tentative collision of the collected spans, front
// to back, with mu the span's scalar majorant per unit t; stops when it returns false. Returns
// false when the walk was stopped (by the callback or the collision guard).
template <typename CollisionFn>
bool for_each_tentative_collision(const MarchScratch& scratch, float dir_length, Pcg32& rng, CollisionFn&& collision) {
  uint32_t count = 0;
  for (const Span& span : scratch.spans) {
    const float mu = span.sigma_maj.max_component() * dir_length;
    if (!(mu > 0.0f)) continue;
    const std::span<const uint32_t> prims(scratch.span_primitives.data() + span.first, span.count);
    for (float t = span.t0 + exponential_step(mu, rng); t < span.t1; t += exponential_step(mu, rng)) {
      if (++count > kMaxTrackingCollisions) return false;
      if (!collision(t, prims, mu)) return false;
    }
  }
  return true;
}

}  // namespace

TrackedSegment track_free_flight(const VolumeScene& volumes, const Ray& ray, RGB throughput, bool may_scatter,
                                 bool gather_emission, MarchScratch& scratch, Pcg32& rng) {
  TrackedSegment out;
  const float dir_length = length(ray.direction);
  bool done = false;
  const bool walked = for_each_tentative_collision(
      scratch, dir_length, rng, [&](float t, std::span<const uint32_t> prims, float mu) {
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

RGB track_transmittance(const VolumeScene& volumes, const Ray& ray, const MarchSettings& settings,
                        MarchScratch& scratch, Pcg32& rng, int medium) {
  if (!collect_spans(volumes, ray, settings, scratch, medium)) return RGB(1.0f);
  return track_transmittance_collected(volumes, ray, scratch, rng);
}

RGB track_transmittance_collected(const VolumeScene& volumes, const Ray& ray, MarchScratch& scratch, Pcg32& rng) {
  const float dir_length = length(ray.direction);
  RGB tr(1.0f);
  const bool walked = for_each_tentative_collision(
      scratch, dir_length, rng, [&](float t, std::span<const uint32_t> prims, float mu) {
        ++scratch.steps;
        scratch.shader_evaluations += prims.size();
        const StepCoefficients c = shade_span(volumes, prims, ray.at(t), dir_length, scratch.volume, nullptr);
        tr *= (RGB(mu) - c.sigma_t) * (1.0f / mu);
        return survive_roulette(tr, rng);
      });
  return walked ? tr : RGB(0.0f);
}

}  // namespace caligo
