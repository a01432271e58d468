#include "integrators/reference.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <variant>

#include "core/overloaded.h"
#include "core/parallel.h"
#include "integrators/interface_eta.h"
#include "lights/light_sample.h"
#include "materials/bsdf.h"
#include "media/medium_stack.h"
#include "raymarch/spans.h"

namespace caligo {
namespace {

// Shadow rays stop this fraction short of a light sample so they do not hit the light itself.
constexpr float kShadowEpsilon = 1e-4f;
// Midpoint steps per primitive for the single-scattering estimator's transmittances.
constexpr int kTransmittanceSteps = 64;
// Light samples per distance sample for lights with area or solid angle.
constexpr int kAreaLightSamples = 4;

Vec2 next_2d(Pcg32& rng) {
  const float a = rng.next_float();
  return {a, rng.next_float()};
}

// An RGB with `value` in one channel and zero in the others.
RGB in_channel(int channel, float value) {
  return {channel == 0 ? value : 0.0f, channel == 1 ? value : 0.0f, channel == 2 ? value : 0.0f};
}

// A priority surface the path crossed on its way to the surface it sees, at ray parameter t:
// a false hit by the medium stack's rules (or, for single scattering, a real null boundary).
struct Crossed {
  float t;
  MediumEntry entry;
};

// Applies the crossings before t_limit to the stack (false hits leave its medium unchanged).
void cross_before(MediumStack& stack, const std::vector<Crossed>& crossed, float t_limit) {
  for (const Crossed& c : crossed)
    if (c.t < t_limit) stack.cross(c.entry);
}

// The surface a path in the media of `stack` sees next along `ray`, walking every crossing in
// order (EmbreeScene::all_hits): Off null surfaces are invisible; priority surfaces whose
// crossing the rules call false are passed and listed in `crossed` (not applied to `stack`).
// The seen surface's own crossing is not applied either: a dielectric may reflect.
std::optional<SurfaceHit> nearest_seen_hit(const Scene& scene, const Ray& ray, const MediumStack& stack,
                                           std::vector<Crossed>& crossed) {
  thread_local std::vector<SurfaceHit> hits;
  crossed.clear();
  scene.surfaces().all_hits(ray, hits);
  MediumStack walk = stack;
  for (const SurfaceHit& h : hits) {
    const auto entry = scene.medium_entry(h.geom_id);
    if (!entry) {
      if (!std::holds_alternative<NullBsdf>(scene.material(h).bsdf)) return h;
      continue;
    }
    if (walk.peek(*entry).real) return h;
    walk.cross(*entry);
    crossed.push_back({h.t, *entry});
  }
  return std::nullopt;
}

// A stretch [t0, t1) of a ray in one medium of the stack (a scene medium slot, -1: vacuum).
struct MediumRun {
  float t0, t1;
  int medium;
};

enum class Blocking {
  kNone,    // no surface blocks (the stretch of a path the caller knows to be clear)
  kShadow,  // a shadow ray's: Off non-null surfaces block, priority dielectrics block unless the
            // scene's render.priority_shadows, null surfaces never do
};

// The stretches of `ray` within [ray.tmin, ray.tmax) starting in the media of `stack`, or
// nullopt when a surface blocks it. Each crossing of a priority surface updates the stack (no
// Fresnel, no refraction); each stretch lies in the medium the rules give it.
std::optional<std::vector<MediumRun>> medium_runs(const Scene& scene, const Ray& ray, MediumStack stack,
                                                  Blocking blocking) {
  thread_local std::vector<SurfaceHit> hits;
  scene.surfaces().all_hits(ray, hits);
  std::vector<MediumRun> runs;
  float t0 = ray.tmin;
  for (const SurfaceHit& h : hits) {
    const bool null = std::holds_alternative<NullBsdf>(scene.material(h).bsdf);
    const auto entry = scene.medium_entry(h.geom_id);
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

// A shadow ray's stretches (Blocking::kShadow). A light that casts no shadows sees the
// origin's medium along the whole ray, as in production.
std::optional<std::vector<MediumRun>> shadow_runs(const Scene& scene, const Ray& ray, bool casts_shadows,
                                                  const MediumStack& stack) {
  if (!casts_shadows) return std::vector<MediumRun>{{ray.tmin, ray.tmax, stack.current().medium}};
  return medium_runs(scene, ray, stack, Blocking::kShadow);
}

// The shadow ray from `origin` (possibly offset off the surface the sample was taken at,
// `sampled_from`) to a light sample: unit direction, aimed at the sampled point and stopping
// short of it. The distance is measured from the origin: the sample's own distance, taken from
// `sampled_from`, would let a ray from an offset origin reach the light's surface.
Ray shadow_ray(Vec3 origin, Vec3 sampled_from, const LightSample& ls) {
  if (!std::isfinite(ls.distance)) return Ray{origin, ls.wi, 0.0f, kInfinity};
  const Vec3 to_light = sampled_from + ls.wi * ls.distance - origin;
  const float d = length(to_light);
  return Ray{origin, to_light / d, 0.0f, d * (1.0f - kShadowEpsilon)};
}

// One majorant interval of a primitive along a ray, [t0, t1) (half-open, so a point on the
// boundary of a grid primitive's touching intervals is shaded once).
struct Stretch {
  float t0, t1;
  const VolumePrimitive* primitive;
};

// A stretch of the ray with one majorant (the sum over the intervals covering it).
struct MajorantPiece {
  float t0, t1;
  float majorant;
};

// The ladder's own per-thread volume state: one context for interval queries and grid lookups.
VolumeContext& context() {
  thread_local VolumeContext c;
  return c;
}

// The media along one ray within [ray.tmin, t_max]: every primitive's majorant intervals
// (and, for `medium` >= 0, the stack medium the ray is in, over the whole stretch), their hull
// [t_lo, t_hi], and (for tracking in one channel) the piecewise-constant majorant
// over the hull, from the intervals' own bounds (so a grid's empty blocks are skipped and its
// dense ones get a tight bound).
struct Segment {
  Ray ray;
  std::vector<Stretch> stretches;
  std::vector<MajorantPiece> pieces;  // ordered along the ray, disjoint
  float t_lo = kInfinity, t_hi = -kInfinity;

  bool empty() const { return stretches.empty(); }
  bool contains(const Stretch& s, float t) const { return t >= s.t0 && t < s.t1; }
};

Segment make_segment(const Scene& scene, const Ray& ray, float t_max, int channel = 0, int medium = -1) {
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
// Sum over the primitives at x(t) of sigma_s,i phase_i(wo, wi): the scattering coefficient
// times the exact per-channel phase mixture.
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

struct ChannelCoefficients {
  float sigma_s = 0.0f, sigma_t = 0.0f;
};

ChannelCoefficients coefficients(const Segment& seg, float t, int channel) {
  const Vec3 x = seg.ray.at(t);
  ChannelCoefficients c;
  for (const Stretch& s : seg.stretches) {
    if (!seg.contains(s, t)) continue;
    const MediumSample m = shade_volume(*s.primitive, x, context());
    c.sigma_s += m.sigma_s[channel];
    c.sigma_t += m.sigma_t()[channel];
  }
  return c;
}

// Optical depth along `ray` over [ray.tmin, t_max] of the volume primitives and the stack
// medium `medium` (-1: none), by the midpoint rule on each majorant interval (primitives add,
// so this equals integrating their sum; per-interval stretches keep a homogeneous primitive
// exact instead of blurring its boundary across a step). An unbounded medium over an unbounded
// ray has infinite depth in every channel where it extinguishes.
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

// exp(-optical depth) over the stretches of `ray`, each in its own stack medium.
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

// ---- single scattering ----

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

// ---- delta tracking, one channel ----

// Tentative collisions of the segment's piecewise-constant majorant, front to back: the
// memoryless exponential restarts at each piece's start. `visit(t, majorant)` returns false
// to stop; returns whether it stopped.
template <typename Visit>
bool walk_tentative_collisions(const Segment& seg, Pcg32& rng, Visit&& visit) {
  for (const MajorantPiece& piece : seg.pieces) {
    if (!(piece.majorant > 0.0f)) continue;
    for (float t = piece.t0;;) {
      const float next = t - std::log(1.0f - rng.next_float()) / piece.majorant;
      // A step below float's resolution of t (a huge majorant far away) cannot advance: stop.
      if (!(next > t) || next >= piece.t1) break;
      t = next;
      if (!visit(t, piece.majorant)) return true;
    }
  }
  return false;
}

// The first real collision in the segment (delta tracking), or none.
std::optional<float> sample_collision(const Segment& seg, int channel, Pcg32& rng) {
  float hit = 0.0f;
  const bool collided = walk_tentative_collisions(seg, rng, [&](float t, float majorant) {
    hit = t;
    return !(rng.next_float() * majorant < coefficients(seg, t, channel).sigma_t);
  });
  return collided ? std::optional<float>(hit) : std::nullopt;
}

// Unbiased transmittance estimate over the segment (ratio tracking).
float ratio_tracking(const Segment& seg, int channel, Pcg32& rng) {
  float tr = 1.0f;
  walk_tentative_collisions(seg, rng, [&](float t, float majorant) {
    tr *= 1.0f - coefficients(seg, t, channel).sigma_t / majorant;
    return tr != 0.0f;  // an unbounded medium's stretch ends only here
  });
  return tr;
}

// Light arriving at `origin`, in the media of `stack`, from a light sample: surfaces block as
// shadow_runs says, each stretch is ratio-tracked in its own medium.
float light_transmittance(const Scene& scene, int light, Vec3 origin, Vec3 sampled_from, const LightSample& ls,
                          const MediumStack& stack, int channel, Pcg32& rng) {
  const Ray shadow = shadow_ray(origin, sampled_from, ls);
  const auto runs = shadow_runs(scene, shadow, scene.casts_shadows(light), stack);
  if (!runs) return 0.0f;
  float tr = 1.0f;
  for (const MediumRun& run : *runs) {
    if (!(run.t1 > run.t0)) continue;
    tr *= ratio_tracking(make_segment(scene, Ray{origin, shadow.direction, run.t0, kInfinity}, run.t1, channel, run.medium),
                         channel, rng);
    if (tr == 0.0f) break;
  }
  return tr;
}

// Next-event estimation at a medium collision: every light, one sample each.
float medium_direct_light(const Scene& scene, const Segment& seg, float t, float sigma_s,
                          const MediumStack& stack, int channel, Pcg32& rng) {
  const Vec3 x = seg.ray.at(t);
  float sum = 0.0f;
  for (size_t i = 0; i < scene.lights().size(); ++i) {
    const auto ls = sample_light(scene.lights()[i], x, next_2d(rng));
    if (!ls || ls->radiance.is_black() || !(ls->pdf > 0.0f)) continue;
    const float phase = scattering_times_phase(seg, t, seg.ray.direction, ls->wi)[channel] / sigma_s;
    if (!(phase > 0.0f)) continue;
    sum += phase * ls->radiance[channel] * light_transmittance(scene, int(i), x, x, *ls, stack, channel, rng) /
           ls->pdf;
  }
  return sum;
}

// A new direction from the phase mixture at x(t) in this channel: a lobe chosen with
// probability sigma_s,i / sigma_s, then sampled exactly, so the path weight stays 1.
Vec3 sample_phase_mixture(const Segment& seg, float t, float sigma_s, int channel, Pcg32& rng) {
  const Vec3 x = seg.ray.at(t);
  const float pick = rng.next_float() * sigma_s;
  float acc = 0.0f;
  const PhaseFunction* chosen = nullptr;
  for (const Stretch& s : seg.stretches) {
    if (!seg.contains(s, t)) continue;
    const MediumSample m = shade_volume(*s.primitive, x, context());
    if (!(m.sigma_s[channel] > 0.0f)) continue;
    chosen = &s.primitive->shader.phase;
    acc += m.sigma_s[channel];
    if (pick < acc) break;
  }
  return phase_sample(*chosen, seg.ray.direction, next_2d(rng)).wi;
}

float surface_direct_light(const Scene& scene, const SurfaceInteraction& si, Vec3 wo, const MediumStack& stack,
                           int channel, Pcg32& rng) {
  float sum = 0.0f;
  for (size_t i = 0; i < scene.lights().size(); ++i) {
    const auto ls = sample_light(scene.lights()[i], si.p, next_2d(rng));
    if (!ls || ls->radiance.is_black() || !(ls->pdf > 0.0f)) continue;
    if (dot(si.ng, ls->wi) * dot(si.ng, wo) <= 0.0f) continue;
    const float f = bsdf_eval(si.material->bsdf, si.ns, wo, ls->wi)[channel] * abs_dot(si.ns, ls->wi);
    if (!(f > 0.0f)) continue;
    const Vec3 origin = offset_ray_origin(si.p, si.ng, ls->wi);
    sum += f * ls->radiance[channel] * light_transmittance(scene, int(i), origin, si.p, *ls, stack, channel, rng) /
           ls->pdf;
  }
  return sum;
}

// `camera_view`: the ray left the camera through specular events only, so an environment
// with visible = false is not seen (EnvironmentLight::visible).
RGB environment(const Scene& scene, Vec3 w, bool camera_view) {
  RGB sum;
  for (int i : scene.infinite_lights()) {
    const Light& light = scene.lights()[size_t(i)];
    const auto* env = std::get_if<EnvironmentLight>(&light);
    if (!(env && !env->visible && camera_view)) sum += escaped_radiance(light, w);
  }
  return sum;
}

RGB surface_emission(const SurfaceInteraction& si, Vec3 wo) {
  const bool front = dot(si.ng, wo) > 0.0f || si.material->two_sided_emission;
  return front ? si.material->emission : RGB(0.0f);
}

}  // namespace

RGB reference_transmittance(const Scene& scene, const Ray& ray, float t_max, int steps) {
  return exp_neg(optical_depth(scene, ray, t_max, steps, -1));
}

RGB reference_transmittance(const Scene& scene, const Ray& ray, float t_max, int steps, const MediumStack& stack) {
  Ray clipped = ray;
  clipped.tmax = t_max;
  return transmittance_of_runs(scene, ray, *medium_runs(scene, clipped, stack, Blocking::kNone), steps);
}

RGB reference_single_scattering(const Scene& scene, const Ray& ray, int samples, Pcg32& rng) {
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

// What the ladder does at a surface, by its material: a visit with one case per BSDF, so a new
// BSDF does not compile until the ladder handles it (it used to absorb silently).
enum class SurfaceStep { kCross, kSpecular, kDiffuse, kAbsorb };
SurfaceStep surface_step(const Bsdf& bsdf) {
  return std::visit(Overloaded{[](const NullBsdf&) { return SurfaceStep::kCross; },
                               [](const DielectricBsdf&) { return SurfaceStep::kSpecular; },
                               [](const DiffuseBsdf&) { return SurfaceStep::kDiffuse; },
                               [](const BlackBsdf&) { return SurfaceStep::kAbsorb; }},
                    bsdf);
}

// One ladder path's state (one channel).
struct LadderPath {
  int channel = 0;
  float radiance = 0.0f, throughput = 1.0f;
  // Emission the ray reaches counts only when the ray left the camera or a specular event;
  // after a diffuse or phase event next-event estimation has already counted it.
  bool count_emission = true;
  bool camera_view = true;  // only specular events so far
  MediumStack stack;
  std::vector<Crossed> crossed;  // false hits in front of the seen surface
  Ray ray;
  int surface_bounces = 0, volume_bounces = 0, boundary_crossings = 0;
  int volume_runs = 0;  // runs of consecutive volume events count once against max_bounces
  bool in_volume_run = false;
};

// A real collision at t of the path's segment: absorbed (probability sigma_a / sigma_t), out of
// scattering events, or a phase event with its light connection. False when the path ends.
bool ladder_collision(const Scene& scene, const Segment& seg, float t, PathLimits limits, LadderPath& p,
                      Pcg32& rng) {
  const ChannelCoefficients c = coefficients(seg, t, p.channel);
  if (rng.next_float() * c.sigma_t >= c.sigma_s || p.volume_bounces >= limits.max_volume_bounces ||
      (!p.in_volume_run && p.surface_bounces + p.volume_runs >= limits.max_bounces))
    return false;
  cross_before(p.stack, p.crossed, t);
  p.radiance += p.throughput * medium_direct_light(scene, seg, t, c.sigma_s, p.stack, p.channel, rng);
  p.ray = Ray{p.ray.at(t), sample_phase_mixture(seg, t, c.sigma_s, p.channel, rng), 0.0f, kInfinity};
  ++p.volume_bounces;
  if (!p.in_volume_run) ++p.volume_runs;
  p.in_volume_run = true;
  p.count_emission = false;
  p.camera_view = false;
  return true;
}

// The surface the path sees: a real null crossing, glass, a diffuse event with its light
// connection, or a black surface that absorbs. False when the path ends.
bool ladder_surface(const Scene& scene, const SurfaceHit& hit, PathLimits limits, LadderPath& p, Pcg32& rng) {
  const SurfaceInteraction si = scene.interaction(p.ray, hit);
  const Vec3 wo = -p.ray.direction;
  const std::optional<MediumEntry> entry = scene.medium_entry(hit.geom_id);
  const Bsdf& bsdf = si.material->bsdf;
  const SurfaceStep step = surface_step(bsdf);
  if (step == SurfaceStep::kCross) {
    // A priority null surface whose crossing is real (Off ones are never seen): the medium
    // changes, nothing else happens.
    p.stack.cross(*entry);
    p.ray = Ray{offset_ray_origin(si.p, si.ng, p.ray.direction), p.ray.direction, 0.0f, kInfinity};
    return ++p.boundary_crossings <= kMaxNullCrossings;
  }
  if (p.count_emission) p.radiance += p.throughput * surface_emission(si, wo)[p.channel];
  if (p.surface_bounces + p.volume_runs >= limits.max_bounces || step == SurfaceStep::kAbsorb) return false;
  std::optional<BsdfSample> bs;
  if (step == SurfaceStep::kSpecular) {
    // Specular: no next-event estimation, so emission the new ray reaches counts.
    const float ior = std::get<DielectricBsdf>(bsdf).ior;
    const Bsdf interface = DielectricBsdf{interface_eta(p.stack, entry, ior, dot(si.ng, wo) > 0.0f)};
    const float u_lobe = rng.next_float();
    bs = bsdf_sample(interface, si.ns, wo, u_lobe, next_2d(rng));
    if (!bs) return false;
    // Only a transmitted path gets past the surface (and a priority surface's medium with it).
    if (entry && dot(si.ng, bs->wi) * dot(si.ng, wo) < 0.0f) p.stack.cross(*entry);
    p.count_emission = true;
  } else {  // SurfaceStep::kDiffuse
    p.radiance += p.throughput * surface_direct_light(scene, si, wo, p.stack, p.channel, rng);
    const float u_lobe = rng.next_float();
    bs = bsdf_sample(bsdf, si.ns, wo, u_lobe, next_2d(rng));
    if (!bs || dot(si.ng, bs->wi) * dot(si.ng, wo) <= 0.0f) return false;
    p.count_emission = false;
    p.camera_view = false;
  }
  p.throughput *= bs->weight[p.channel];
  p.ray = Ray{offset_ray_origin(si.p, si.ng, bs->wi), bs->wi, 0.0f, kInfinity};
  ++p.surface_bounces;
  p.in_volume_run = false;
  return true;
}

RGB reference_delta_tracking(const Scene& scene, const Ray& camera_ray, PathLimits limits, Pcg32& rng) {
  LadderPath p;
  p.channel = std::min(int(rng.next_float() * 3.0f), 2);
  p.stack = scene.camera_stack();
  p.ray = camera_ray;
  while (p.throughput > 0.0f) {
    const auto hit = nearest_seen_hit(scene, p.ray, p.stack, p.crossed);
    const Segment seg = make_segment(scene, p.ray, hit ? hit->t : kInfinity, p.channel, p.stack.current().medium);
    if (const auto t = sample_collision(seg, p.channel, rng)) {
      if (!ladder_collision(scene, seg, *t, limits, p, rng)) break;
      continue;
    }
    cross_before(p.stack, p.crossed, kInfinity);
    if (!hit) {
      if (p.count_emission) p.radiance += p.throughput * environment(scene, p.ray.direction, p.camera_view)[p.channel];
      break;
    }
    if (!ladder_surface(scene, *hit, limits, p, rng)) break;
  }
  return in_channel(p.channel, 3.0f * p.radiance);
}

std::vector<RGB> reference_image(const Scene& scene, Vec2i resolution, const ReferenceOptions& options) {
  const Camera camera = scene.camera(resolution);
  std::vector<RGB> pixels(size_t(resolution.x) * size_t(resolution.y));
  parallel_for(resolution.y, [&](int y) {
    for (int x = 0; x < resolution.x; ++x) {
      Pcg32 rng(hash_values(options.seed, uint64_t(x), uint64_t(y)), 0x5eed);
      double r = 0, g = 0, b = 0;
      for (int s = 0; s < options.samples_per_pixel; ++s) {
        const Vec2 jitter = next_2d(rng);
        // The lens sample is drawn only for a thin lens, so pinhole images keep their random stream.
        const Vec2 lens = camera.has_aperture() ? next_2d(rng) : Vec2{0.5f, 0.5f};
        const Ray ray = camera.generate_ray({float(x) + jitter.x, float(y) + jitter.y}, lens);
        const RGB v = options.estimator == ReferenceEstimator::kSingleScattering
                          ? reference_single_scattering(scene, ray, options.distance_samples, rng)
                          : reference_delta_tracking(scene, ray, options.limits, rng);
        r += v.r, g += v.g, b += v.b;
      }
      const double n = std::max(1, options.samples_per_pixel);
      pixels[size_t(y) * size_t(resolution.x) + size_t(x)] = RGB(float(r / n), float(g / n), float(b / n));
    }
  });
  return pixels;
}

RGB reference_mean_radiance(const Scene& scene, Vec2i resolution, const ReferenceOptions& options) {
  double r = 0, g = 0, b = 0;
  const std::vector<RGB> pixels = reference_image(scene, resolution, options);
  for (const RGB& p : pixels) r += p.r, g += p.g, b += p.b;
  const double n = double(std::max<size_t>(1, pixels.size()));
  return RGB(float(r / n), float(g / n), float(b / n));
}

RGB reference_mean_radiance(const Scene& scene, Vec2i resolution, int samples_per_pixel,
                            ReferenceEstimator which, uint64_t seed) {
  ReferenceOptions options;
  options.estimator = which;
  options.samples_per_pixel = samples_per_pixel;
  options.seed = seed;
  return reference_mean_radiance(scene, resolution, options);
}

}  // namespace caligo
