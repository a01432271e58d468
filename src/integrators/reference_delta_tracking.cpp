// Rung 3 of the reference ladder (reference.h): all orders of scattering by delta tracking
// in one colour channel, next-event estimation with ratio tracking.
#include "integrators/reference.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <variant>
#include <vector>

#include "core/overloaded.h"
#include "integrators/interface_eta.h"
#include "integrators/reference_internal.h"
#include "lights/light_sample.h"
#include "materials/bsdf.h"
#include "media/medium_stack.h"

namespace caligo {

using namespace reference_detail;

namespace {

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
// order (EmbreeScene::all_hits): Off null surfaces are invisible, partly transparent ones seen by
// chance; priority surfaces whose
// crossing the rules call false are passed and listed in `crossed` (not applied to `stack`).
// The seen surface's own crossing is not applied either: a dielectric may reflect.
std::optional<SurfaceHit> nearest_seen_hit(const Scene& scene, const Ray& ray, const MediumStack& stack,
                                           std::vector<Crossed>& crossed, Pcg32& rng) {
  thread_local std::vector<SurfaceHit> hits;
  crossed.clear();
  scene.surfaces().all_hits(ray, hits);
  MediumStack walk = stack;
  for (const SurfaceHit& h : hits) {
    const auto entry = scene.medium_entry(h.geom_id);
    if (!entry) {
      // A partly transparent surface is met with probability its opacity (unlike production's
      // layers in the record: an independent check).
      if (scene.is_transparent(h.geom_id) && !(rng.next_float() < scene.opacity(h))) continue;
      if (!std::holds_alternative<NullBsdf>(scene.material(h).bsdf)) return h;
      continue;
    }
    if (walk.peek(*entry).real) return h;
    walk.cross(*entry);
    crossed.push_back({h.t, *entry});
  }
  return std::nullopt;
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
  float tr = 1.0f;  // starts with what partly transparent surfaces let through
  const auto runs = shadow_runs(scene, shadow, scene.casts_shadows(light), stack, &tr);
  if (!runs || tr == 0.0f) return 0.0f;
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

}  // namespace

RGB reference_delta_tracking(const Scene& scene, const Ray& camera_ray, PathLimits limits, Pcg32& rng) {
  LadderPath p;
  p.channel = std::min(int(rng.next_float() * 3.0f), 2);
  p.stack = scene.camera_stack();
  p.ray = camera_ray;
  while (p.throughput > 0.0f) {
    const auto hit = nearest_seen_hit(scene, p.ray, p.stack, p.crossed, rng);
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

}  // namespace caligo
