// The reference ladder's shared helpers (reference_internal.h): media along a ray, shadow
// rays, segments and the scattering along them, midpoint-rule optical depth.
#include "integrators/reference_internal.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <variant>
#include <vector>

#include "materials/bsdf.h"
#include "raymarch/spans.h"

namespace caligo::reference_detail {
namespace {

// Shadow rays stop this fraction short of a light sample so they do not hit the light itself.
constexpr float kShadowEpsilon = 1e-4f;

}  // namespace

Vec2 next_2d(Pcg32& rng) {
  const float a = rng.next_float();
  return {a, rng.next_float()};
}

std::optional<std::vector<MediumRun>> medium_runs(const Scene& scene, const Ray& ray, MediumStack stack,
                                                  Blocking blocking, float* through) {
  thread_local std::vector<SurfaceHit> hits;
  scene.surfaces().all_hits(ray, hits);
  std::vector<MediumRun> runs;
  float t0 = ray.tmin;
  for (const SurfaceHit& h : hits) {
    const bool null = std::holds_alternative<NullBsdf>(scene.material(h).bsdf);
    const auto entry = scene.medium_entry(h.geom_id);
    if (blocking == Blocking::kShadow && through && scene.is_transparent(h.geom_id)) {
      *through *= 1.0f - scene.opacity(h);
      continue;
    }
    if (blocking == Blocking::kShadow &&
        ((!entry && !null) || (entry && !null && !scene.desc().render.path.priority_shadows)))
      return std::nullopt;
    if (!entry) continue;
    runs.push_back({t0, h.t, stack.current().medium});
    stack.cross(*entry);
    t0 = h.t;
  }
  runs.push_back({t0, ray.tmax, stack.current().medium});
  return runs;
}

std::optional<std::vector<MediumRun>> shadow_runs(const Scene& scene, const Ray& ray, bool casts_shadows,
                                                  const MediumStack& stack, float* through) {
  if (!casts_shadows) return std::vector<MediumRun>{{ray.tmin, ray.tmax, stack.current().medium}};
  return medium_runs(scene, ray, stack, Blocking::kShadow, through);
}

Ray shadow_ray(Vec3 origin, Vec3 sampled_from, const LightSample& ls) {
  if (!std::isfinite(ls.distance)) return Ray{origin, ls.wi, 0.0f, kInfinity};
  const Vec3 to_light = sampled_from + ls.wi * ls.distance - origin;
  const float d = length(to_light);
  return Ray{origin, to_light / d, 0.0f, d * (1.0f - kShadowEpsilon)};
}

VolumeContext& context() {
  thread_local VolumeContext c;
  return c;
}

Segment make_segment(const Scene& scene, const Ray& ray, float t_max, int channel, int medium) {
  Segment seg{ray, {}};
  Ray clipped = ray;
  clipped.tmax = t_max;
  VolumeContext& ctx = context();
  scene.volumes().intervals(clipped, ctx, medium);
  for (const VolumeInterval& iv : ctx.intervals) {
    seg.stretches.push_back({iv.t0, iv.t1, &scene.volumes().primitive(iv.primitive)});
    seg.t_lo = std::min(seg.t_lo, iv.t0);
    seg.t_hi = std::max(seg.t_hi, iv.t1);
  }
  // Majorants of overlapping intervals add (primitives add their coefficients).
  thread_local std::vector<Span> spans;
  thread_local std::vector<uint32_t> span_primitives;
  build_spans(ctx.intervals, spans, span_primitives);
  for (const Span& span : spans) seg.pieces.push_back({span.t0, span.t1, span.sigma_maj[channel]});
  return seg;
}

RGB scattering_times_phase(const Segment& seg, float t, Vec3 wo, Vec3 wi) {
  const Vec3 x = seg.ray.at(t);
  RGB sum;
  for (const Stretch& s : seg.stretches) {
    if (!seg.contains(s, t)) continue;
    const MediumSample m = shade_volume(*s.primitive, x, context());
    if (!m.sigma_s.is_black()) sum += m.sigma_s * phase_eval(m.phase, wo, wi);
  }
  return sum;
}

RGB optical_depth(const Scene& scene, const Ray& ray, float t_max, int steps, int medium) {
  Ray clipped = ray;
  clipped.tmax = t_max;
  const float metres_per_t = length(ray.direction);
  VolumeContext& ctx = context();
  scene.volumes().intervals(clipped, ctx, medium);
  RGB depth;
  // Shading uses only the context's grid accessors, never its interval list.
  for (const VolumeInterval& iv : ctx.intervals) {
    const VolumePrimitive& p = scene.volumes().primitive(iv.primitive);
    if (!std::isfinite(iv.t1)) {  // only stack media are unbounded, and they are homogeneous
      const RGB sigma_t = shade_volume(p, ray.at(iv.t0), ctx).sigma_t();
      depth += RGB(sigma_t.r > 0.0f ? kInfinity : 0.0f, sigma_t.g > 0.0f ? kInfinity : 0.0f,
                   sigma_t.b > 0.0f ? kInfinity : 0.0f);
      continue;
    }
    const float dt = (iv.t1 - iv.t0) / float(steps);
    RGB sum;
    for (int i = 0; i < steps; ++i) sum += shade_volume(p, ray.at(iv.t0 + (float(i) + 0.5f) * dt), ctx).sigma_t();
    depth += sum * (dt * metres_per_t);
  }
  return depth;
}

RGB transmittance_of_runs(const Scene& scene, const Ray& ray, const std::vector<MediumRun>& runs, int steps) {
  RGB depth;
  for (const MediumRun& run : runs) {
    if (!(run.t1 > run.t0)) continue;
    Ray stretch = ray;
    stretch.tmin = run.t0;
    depth += optical_depth(scene, stretch, run.t1, steps, run.medium);
  }
  return exp_neg(depth);
}

}  // namespace caligo::reference_detail
