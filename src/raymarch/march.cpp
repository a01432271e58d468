#include "raymarch/march.h"

#include <algorithm>
#include <cmath>

namespace caligo {
namespace {

// Radiance emitted over a step of length dt, seen through transmittance T0 at its start:
// integral of T0 e^{-sigma_t s} emission ds over [0, dt].
RGB integrate_emission(RGB t0, RGB sigma_t, RGB emission, float dt) {
  const auto channel = [&](int c) {
    const float st = sigma_t[c];
    const float f = st * dt > 1e-6f ? -std::expm1(-st * dt) / st : dt;
    return t0[c] * emission[c] * f;
  };
  return {channel(0), channel(1), channel(2)};
}

int steps_for_span(const VolumeScene& volumes, const Span& span, std::span<const uint32_t> primitives,
                   float length_m, const MarchSettings& settings) {
  if (span.homogeneous) return 1;
  float h = kInfinity;
  for (uint32_t id : primitives) h = std::min(h, primitive_step_size(volumes.primitive(id), settings));
  // Clamped in float first: a ratio beyond INT_MAX (a tiny step) must not wrap when converted.
  const float n = std::ceil(length_m / h);
  if (!(n < float(settings.max_steps_per_span))) return std::max(1, settings.max_steps_per_span);
  return std::max(1, int(n));
}

// Calls step(t0, t1, t_shade, primitives) for every step of the collected spans, front to back,
// until it returns false.
template <typename StepFn>
void for_each_collected_step(const VolumeScene& volumes, const Ray& ray, float jitter, const MarchSettings& settings,
                             MarchScratch& scratch, StepFn&& step) {
  const float dir_length = length(ray.direction);
  for (const Span& span : scratch.spans) {
    const std::span<const uint32_t> prims(scratch.span_primitives.data() + span.first, span.count);
    const int n = steps_for_span(volumes, span, prims, (span.t1 - span.t0) * dir_length, settings);
    const float dt = (span.t1 - span.t0) / float(n);
    for (int i = 0; i < n; ++i) {
      // Both ends from the same expression, so consecutive steps meet exactly.
      const float a = span.t0 + dt * float(i);
      const float b = i + 1 == n ? span.t1 : span.t0 + dt * float(i + 1);
      // Jittered even when a span is one step (a block clipped to a voxel-thin tight box): a
      // fixed midpoint would bias its optical depth; a homogeneous span reads one value anyway.
      const float t_shade = span.homogeneous ? 0.5f * (a + b) : a + jitter * (b - a);
      ++scratch.steps;
      scratch.shader_evaluations += prims.size();
      if (!step(a, b, t_shade, prims, dir_length)) return;
    }
  }
}

}  // namespace

StepCoefficients shade_span(const VolumeScene& volumes, std::span<const uint32_t> primitives, Vec3 p, float scale,
                            VolumeContext& context, std::vector<PhaseLobe>* lobes) {
  StepCoefficients c;
  if (lobes) lobes->clear();
  for (uint32_t id : primitives) {
    const MediumSample m = shade_volume(volumes.primitive(id), p, context);
    c.sigma_t += m.sigma_t() * scale;
    c.sigma_s += m.sigma_s * scale;
    c.emission += m.emission * scale;
    c.holdout += m.holdout * scale;
    if (lobes && !m.sigma_s.is_black()) lobes->push_back({m.sigma_s * scale, m.phase});
  }
  // Overlapping primitives mix their phase functions in proportion to sigma_s, per channel.
  if (lobes)
    for (PhaseLobe& l : *lobes)
      l.weight = RGB(c.sigma_s.r > 0.0f ? l.weight.r / c.sigma_s.r : 0.0f,
                     c.sigma_s.g > 0.0f ? l.weight.g / c.sigma_s.g : 0.0f,
                     c.sigma_s.b > 0.0f ? l.weight.b / c.sigma_s.b : 0.0f);
  return c;
}

bool collect_spans(const VolumeScene& volumes, const Ray& ray, const MarchSettings& settings, MarchScratch& scratch,
                   int medium) {
  scratch.spans.clear();
  if (volumes.empty() && medium < 0) return false;
  scratch.volume.skip_empty_blocks = settings.skip_empty_blocks;
  scratch.volume.constant_blocks_one_step = settings.constant_blocks_one_step;
  volumes.intervals(ray, scratch.volume, medium);
  const auto& intervals = scratch.volume.intervals;
  const bool one_primitive =
      std::all_of(intervals.begin(), intervals.end(),
                  [&](const VolumeInterval& iv) { return iv.primitive == intervals.front().primitive; });
  if (!intervals.empty() && one_primitive) {
    // The common case needs no sweep: one primitive's intervals are ordered and disjoint.
    for (const VolumeInterval& iv : intervals)
      if (iv.t1 > iv.t0) scratch.spans.push_back({iv.t0, iv.t1, 0, 1, iv.sigma_maj, iv.homogeneous, iv.sigma_min});
    scratch.span_primitives.assign(1, intervals.front().primitive);
  } else {
    build_spans(intervals, scratch.span_scratch, scratch.spans, scratch.span_primitives);
  }
  return !scratch.spans.empty();
}

bool collect_coarse_spans(const VolumeScene& volumes, const Ray& ray, const MarchSettings& settings,
                          MarchScratch& scratch, int medium) {
  MarchSettings coarse = settings;
  coarse.skip_empty_blocks = false;
  return collect_spans(volumes, ray, coarse, scratch, medium);
}

bool collected_spans_emissive(const VolumeScene& volumes, const MarchScratch& scratch) {
  return std::any_of(scratch.span_primitives.begin(), scratch.span_primitives.end(),
                     [&](uint32_t id) { return emits(volumes.primitive(id).shader); });
}

bool collected_spans_homogeneous(const MarchScratch& scratch) {
  return std::all_of(scratch.spans.begin(), scratch.spans.end(), [](const Span& s) { return s.homogeneous; });
}

float primitive_step_size(const VolumePrimitive& primitive, const MarchSettings& settings) {
  const VolumeShader& s = primitive.shader;
  if (is_homogeneous(s)) return kInfinity;
  if (s.step_size > 0.0f) return s.step_size;
  // A grid varies over one voxel; an analytic field over a fraction of its bounds.
  const float voxel = field_voxel_size(primitive);
  float automatic =
      std::isfinite(voxel) ? voxel : settings.auto_step_fraction * length(volume_bounds(primitive.shape).diagonal());
  // Noise varies over one lattice cell (1 / scale metres) whatever the primitive's size.
  if (s.noise) automatic = std::min(automatic, 0.25f / s.noise->scale);
  // Height fog varies over its scale height, whatever the volume's size (a 40 m fog box's
  // 1/64 of a diagonal, 0.9 m, would step over a 0.8 m scale height).
  if (const auto* h = std::get_if<HeightFalloffDensity>(&s.field))
    automatic = std::min(automatic, 0.25f * h->scale_height);
  return automatic * s.step_scale;
}

void march(const VolumeScene& volumes, const Ray& ray, float jitter, const MarchSettings& settings,
           MarchScratch& scratch, TransmittanceRecord& out, int medium) {
  out.clear();
  if (!collect_spans(volumes, ray, settings, scratch, medium)) return;
  march_collected(volumes, ray, jitter, settings, scratch, out);
}

void march_collected(const VolumeScene& volumes, const Ray& ray, float jitter, const MarchSettings& settings,
                     MarchScratch& scratch, TransmittanceRecord& out) {
  out.clear();
  for_each_collected_step(volumes, ray, jitter, settings, scratch,
                [&](float a, float b, float t_shade, std::span<const uint32_t> prims, float scale) {
                  const StepCoefficients c =
                      shade_span(volumes, prims, ray.at(t_shade), scale, scratch.volume, &scratch.lobes);
                  const RGB t_start = out.transmittance_end();
                  if (!c.emission.is_black())
                    out.add_emission(integrate_emission(t_start, c.sigma_t, c.emission, b - a));
                  if (c.holdout > 0.0f)
                    out.add_holdout(integrate_emission(t_start, c.sigma_t, RGB(c.holdout), b - a).average());
                  out.push(a, b, c.sigma_t, c.sigma_s, scratch.lobes);
                  return out.transmittance_end().max_component() >= settings.opacity_threshold;
                });
}

RGB march_transmittance(const VolumeScene& volumes, const Ray& ray, float jitter,
                        const MarchSettings& settings, MarchScratch& scratch, int medium) {
  if (!collect_spans(volumes, ray, settings, scratch, medium)) return RGB(1.0f);
  return march_transmittance_collected(volumes, ray, jitter, settings, scratch);
}

RGB march_transmittance_collected(const VolumeScene& volumes, const Ray& ray, float jitter,
                                  const MarchSettings& settings, MarchScratch& scratch) {
  RGB optical_depth;
  bool opaque = false;
  for_each_collected_step(volumes, ray, jitter, settings, scratch,
                [&](float a, float b, float t_shade, std::span<const uint32_t> prims, float scale) {
                  optical_depth +=
                      shade_span(volumes, prims, ray.at(t_shade), scale, scratch.volume, nullptr).sigma_t *
                      (b - a);
                  opaque = std::min({optical_depth.r, optical_depth.g, optical_depth.b}) >
                           -std::log(settings.opacity_threshold);
                  return !opaque;
                });
  if (opaque) return RGB(0.0f);
  return exp_neg(optical_depth);
}

RGB march_emission(const VolumeScene& volumes, const Ray& ray, float jitter, const MarchSettings& settings,
                   MarchScratch& scratch) {
  if (!collect_spans(volumes, ray, settings, scratch)) return RGB(0.0f);
  RGB tr(1.0f), emission;
  for_each_collected_step(volumes, ray, jitter, settings, scratch,
                [&](float a, float b, float t_shade, std::span<const uint32_t> prims, float scale) {
                  const StepCoefficients c = shade_span(volumes, prims, ray.at(t_shade), scale, scratch.volume, nullptr);
                  if (!c.emission.is_black()) emission += integrate_emission(tr, c.sigma_t, c.emission, b - a);
                  tr *= exp_neg(c.sigma_t * (b - a));
                  return tr.max_component() >= settings.opacity_threshold;
                });
  return emission;
}

}  // namespace caligo
