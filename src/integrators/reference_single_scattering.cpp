// Rung 2 of the reference ladder (reference.h): single scattering by uniform distance
// sampling, with brute-force transmittance on both sides.
#include "integrators/reference.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <variant>
#include <vector>

#include "integrators/reference_internal.h"
#include "lights/light_sample.h"
#include "materials/bsdf.h"

namespace caligo {

using namespace reference_detail;

namespace {

// Midpoint steps per primitive for the single-scattering estimator's transmittances.
constexpr int kTransmittanceSteps = 64;
// Light samples per distance sample for lights with area or solid angle.
constexpr int kAreaLightSamples = 4;

// `stack` after every crossing of a priority surface by `ray` within [ray.tmin, t).
MediumStack stack_along(const Scene& scene, const Ray& ray, float t, MediumStack stack) {
  if (!scene.has_priority_objects()) return stack;
  thread_local std::vector<SurfaceHit> hits;
  Ray clipped = ray;
  clipped.tmax = t;
  scene.surfaces().all_hits(clipped, hits);
  for (const SurfaceHit& h : hits)
    if (const auto entry = scene.medium_entry(h.geom_id)) stack.cross(*entry);
  return stack;
}

// Where a single-scattering camera ray ends, and the media up to there. It ends at the first
// surface that is not a null surface (Off surfaces of any other kind, priority dielectrics
// whose crossing is real); false hits and real null boundaries are crossed. The segment holds
// the volume primitives' intervals up to the end and each stretch's stack medium (no majorant
// pieces: uniform distance sampling needs none).
Segment single_scattering_segment(const Scene& scene, const Ray& ray, const MediumStack& camera_stack) {
  thread_local std::vector<SurfaceHit> hits;
  scene.surfaces().all_hits(ray, hits);
  MediumStack stack = camera_stack;
  std::vector<MediumRun> runs;
  float t0 = ray.tmin, t_end = kInfinity;
  for (const SurfaceHit& h : hits) {
    const bool null = std::holds_alternative<NullBsdf>(scene.material(h).bsdf);
    const auto entry = scene.medium_entry(h.geom_id);
    if (!entry && null) continue;
    if (!entry || (!null && stack.peek(*entry).real)) {
      t_end = h.t;
      break;
    }
    runs.push_back({t0, h.t, stack.current().medium});
    stack.cross(*entry);
    t0 = h.t;
  }
  runs.push_back({t0, t_end, stack.current().medium});
  Segment seg = make_segment(scene, ray, t_end);
  for (const MediumRun& run : runs) {
    if (run.medium < 0 || !(run.t1 > run.t0)) continue;
    const uint32_t id = uint32_t(scene.volumes().primitives().size()) + uint32_t(run.medium);
    seg.stretches.push_back({run.t0, run.t1, &scene.volumes().primitive(id)});
    seg.t_lo = std::min(seg.t_lo, run.t0);
    seg.t_hi = std::max(seg.t_hi, run.t1);
  }
  return seg;
}

// The light of every light scattered once at x(t) towards the ray origin, including the
// transmittance back to the origin, before dividing by the distance pdf.
RGB scattered_once(const Scene& scene, const Segment& seg, float t, const MediumStack& camera_stack, Pcg32& rng) {
  const Ray& ray = seg.ray;
  const Vec3 x = ray.at(t);
  const MediumStack stack_at_x = stack_along(scene, ray, t, camera_stack);
  RGB in_scattered;
  for (size_t i = 0; i < scene.lights().size(); ++i) {
    const Light& light = scene.lights()[i];
    const int n = is_delta(light) ? 1 : kAreaLightSamples;
    for (int k = 0; k < n; ++k) {
      const auto ls = sample_light(light, x, next_2d(rng));
      if (!ls || ls->radiance.is_black() || !(ls->pdf > 0.0f)) continue;
      const RGB f = scattering_times_phase(seg, t, ray.direction, ls->wi);
      if (f.is_black()) continue;
      const Ray shadow = shadow_ray(x, x, *ls);
      const auto runs = shadow_runs(scene, shadow, scene.casts_shadows(int(i)), stack_at_x);
      if (!runs) continue;
      const RGB tr = transmittance_of_runs(scene, shadow, *runs, kTransmittanceSteps);
      in_scattered += f * tr * ls->radiance * (1.0f / (ls->pdf * float(n)));
    }
  }
  if (in_scattered.is_black()) return in_scattered;
  return in_scattered * reference_transmittance(scene, ray, t, kTransmittanceSteps, camera_stack);
}

}  // namespace

RGB reference_single_scattering(const Scene& scene, const Ray& ray, int samples, Pcg32& rng) {
  if (scene.has_transparent_surfaces())
    throw std::invalid_argument(
        "the single-scattering reference does not model partly transparent surfaces; use the delta-tracking rung");
  const MediumStack& camera_stack = scene.camera_stack();
  const Segment seg = single_scattering_segment(scene, ray, camera_stack);
  if (seg.empty() || samples <= 0) return RGB(0.0f);
  const float length = seg.t_hi - seg.t_lo;
  if (!std::isfinite(length))
    throw std::invalid_argument("reference_single_scattering: the ray runs to infinity inside a medium");
  RGB sum;
  for (int i = 0; i < samples; ++i)
    sum += scattered_once(scene, seg, seg.t_lo + rng.next_float() * length, camera_stack, rng);
  return sum * (length / float(samples));  // the uniform pdf is 1 / length
}

}  // namespace caligo
