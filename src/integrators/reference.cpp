#include "integrators/reference.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <variant>

#include "core/parallel.h"
#include "lights/light_sample.h"
#include "materials/bsdf.h"
#include "raymarch/spans.h"

namespace caligo {
namespace {

// Shadow rays stop this fraction short of a light sample so they do not hit the light itself.
constexpr float kShadowEpsilon = 1e-4f;
// Midpoint steps per primitive for the single-scattering estimator's transmittances.
constexpr int kTransmittanceSteps = 64;
// Light samples per distance sample for lights with area or solid angle.
constexpr int kAreaLightSamples = 4;
constexpr int kMaxNullCrossings = 256;

Vec2 next_2d(Pcg32& rng) {
  const float a = rng.next_float();
  return {a, rng.next_float()};
}

RGB exp_negative(RGB depth) { return {std::exp(-depth.r), std::exp(-depth.g), std::exp(-depth.b)}; }

// An RGB with `value` in one channel and zero in the others.
RGB in_channel(int channel, float value) {
  return {channel == 0 ? value : 0.0f, channel == 1 ? value : 0.0f, channel == 2 ? value : 0.0f};
}

// The nearest surface hit that is not a null surface (those are invisible to transport).
std::optional<SurfaceHit> nearest_opaque_hit(const Scene& scene, Ray ray) {
  for (int crossings = 0; crossings < kMaxNullCrossings; ++crossings) {
    const auto hit = scene.surfaces().intersect(ray);
    if (!hit || !std::holds_alternative<NullBsdf>(scene.material(*hit).bsdf)) return hit;
    ray.tmin = hit->t + std::max(1e-4f, hit->t * 1e-5f);
  }
  return std::nullopt;
}

// True when no shadow-casting surface lies between `origin` and the light sample.
bool unoccluded(const Scene& scene, int light, Vec3 origin, const LightSample& ls) {
  if (!scene.casts_shadows(light)) return true;
  const float tmax = std::isfinite(ls.distance) ? ls.distance * (1.0f - kShadowEpsilon) : kInfinity;
  return !scene.surfaces().occluded(Ray{origin, ls.wi, 0.0f, tmax});
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

// The media along one ray within [ray.tmin, t_max]: every primitive's majorant intervals,
// their hull [t_lo, t_hi], and (for tracking in one channel) the piecewise-constant majorant
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

Segment make_segment(const Scene& scene, const Ray& ray, float t_max, int channel = 0) {
  Segment seg{ray, {}};
  Ray clipped = ray;
  clipped.tmax = t_max;
  VolumeContext& ctx = context();
  scene.volumes().intervals(clipped, ctx);
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

// ---- single scattering ----

// The light of every light scattered once at x(t) towards the ray origin, including the
// transmittance back to the origin, before dividing by the distance pdf.
RGB scattered_once(const Scene& scene, const Segment& seg, float t, Pcg32& rng) {
  const Ray& ray = seg.ray;
  const Vec3 x = ray.at(t);
  RGB in_scattered;
  for (size_t i = 0; i < scene.lights().size(); ++i) {
    const Light& light = scene.lights()[i];
    const int n = is_delta(light) ? 1 : kAreaLightSamples;
    for (int k = 0; k < n; ++k) {
      const auto ls = sample_light(light, x, next_2d(rng));
      if (!ls || ls->radiance.is_black() || !(ls->pdf > 0.0f)) continue;
      const RGB f = scattering_times_phase(seg, t, ray.direction, ls->wi);
      if (f.is_black() || !unoccluded(scene, int(i), x, *ls)) continue;
      const RGB tr =
          reference_transmittance(scene, Ray{x, ls->wi, 0.0f, kInfinity}, ls->distance, kTransmittanceSteps);
      in_scattered += f * tr * ls->radiance * (1.0f / (ls->pdf * float(n)));
    }
  }
  if (in_scattered.is_black()) return in_scattered;
  return in_scattered * reference_transmittance(scene, ray, t, kTransmittanceSteps);
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
    return true;
  });
  return tr;
}

// Light arriving at `origin` from a light sample: surfaces block, media attenuate.
float light_transmittance(const Scene& scene, int light, Vec3 origin, const LightSample& ls, int channel,
                          Pcg32& rng) {
  if (!unoccluded(scene, light, origin, ls)) return 0.0f;
  return ratio_tracking(make_segment(scene, Ray{origin, ls.wi, 0.0f, kInfinity}, ls.distance, channel),
                        channel, rng);
}

// Next-event estimation at a medium collision: every light, one sample each.
float medium_direct_light(const Scene& scene, const Segment& seg, float t, float sigma_s, int channel,
                          Pcg32& rng) {
  const Vec3 x = seg.ray.at(t);
  float sum = 0.0f;
  for (size_t i = 0; i < scene.lights().size(); ++i) {
    const auto ls = sample_light(scene.lights()[i], x, next_2d(rng));
    if (!ls || ls->radiance.is_black() || !(ls->pdf > 0.0f)) continue;
    const float phase = scattering_times_phase(seg, t, seg.ray.direction, ls->wi)[channel] / sigma_s;
    if (!(phase > 0.0f)) continue;
    sum += phase * ls->radiance[channel] * light_transmittance(scene, int(i), x, *ls, channel, rng) / ls->pdf;
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

float surface_direct_light(const Scene& scene, const SurfaceInteraction& si, Vec3 wo, int channel,
                           Pcg32& rng) {
  float sum = 0.0f;
  for (size_t i = 0; i < scene.lights().size(); ++i) {
    const auto ls = sample_light(scene.lights()[i], si.p, next_2d(rng));
    if (!ls || ls->radiance.is_black() || !(ls->pdf > 0.0f)) continue;
    if (dot(si.ng, ls->wi) * dot(si.ng, wo) <= 0.0f) continue;
    const float f = bsdf_eval(si.material->bsdf, si.ns, wo, ls->wi)[channel] * abs_dot(si.ns, ls->wi);
    if (!(f > 0.0f)) continue;
    const Vec3 origin = offset_ray_origin(si.p, si.ng, ls->wi);
    sum += f * ls->radiance[channel] * light_transmittance(scene, int(i), origin, *ls, channel, rng) / ls->pdf;
  }
  return sum;
}

// What the ladder does at each kind of surface: diffuse ones scatter, black ones absorb, null
// ones never get here (nearest_opaque_hit crosses them), dielectrics are out of its scope.
struct ScattersDiffusely {
  bool operator()(const DiffuseBsdf&) const { return true; }
  bool operator()(const BlackBsdf&) const { return false; }
  bool operator()(const NullBsdf&) const { return false; }
  bool operator()(const DielectricBsdf&) const {
    throw std::invalid_argument("reference_delta_tracking: dielectrics are not supported");
  }
};

RGB environment(const Scene& scene, Vec3 w) {
  RGB sum;
  for (int i : scene.infinite_lights()) sum += escaped_radiance(scene.lights()[size_t(i)], w);
  return sum;
}

RGB surface_emission(const SurfaceInteraction& si, Vec3 wo) {
  const bool front = dot(si.ng, wo) > 0.0f || si.material->two_sided_emission;
  return front ? si.material->emission : RGB(0.0f);
}

}  // namespace

RGB reference_transmittance(const Scene& scene, const Ray& ray, float t_max, int steps) {
  Ray clipped = ray;
  clipped.tmax = t_max;
  const float metres_per_t = length(ray.direction);
  VolumeContext& ctx = context();
  scene.volumes().intervals(clipped, ctx);
  RGB depth;
  // Shading uses only the context's grid accessors, never its interval list.
  for (const VolumeInterval& iv : ctx.intervals) {
    const VolumePrimitive& p = scene.volumes().primitive(iv.primitive);
    const float dt = (iv.t1 - iv.t0) / float(steps);
    RGB sum;
    for (int i = 0; i < steps; ++i) sum += shade_volume(p, ray.at(iv.t0 + (float(i) + 0.5f) * dt), ctx).sigma_t();
    depth += sum * (dt * metres_per_t);
  }
  return exp_negative(depth);
}

RGB reference_single_scattering(const Scene& scene, const Ray& ray, int samples, Pcg32& rng) {
  const auto hit = nearest_opaque_hit(scene, ray);
  const Segment seg = make_segment(scene, ray, hit ? hit->t : kInfinity);
  if (seg.empty() || samples <= 0) return RGB(0.0f);
  const float length = seg.t_hi - seg.t_lo;
  RGB sum;
  for (int i = 0; i < samples; ++i)
    sum += scattered_once(scene, seg, seg.t_lo + rng.next_float() * length, rng);
  return sum * (length / float(samples));  // the uniform pdf is 1 / length
}

RGB reference_delta_tracking(const Scene& scene, const Ray& camera_ray, ReferenceLimits limits, Pcg32& rng) {
  const int channel = std::min(int(rng.next_float() * 3.0f), 2);
  float radiance = 0.0f, throughput = 1.0f;
  bool direct = true;  // no scattering yet: the camera sees what this ray reaches
  Ray ray = camera_ray;
  int surface_bounces = 0, volume_bounces = 0;
  int volume_runs = 0;  // runs of consecutive volume events count once against max_surface_bounces
  bool in_volume_run = false;
  while (throughput > 0.0f) {
    const auto hit = nearest_opaque_hit(scene, ray);
    const Segment seg = make_segment(scene, ray, hit ? hit->t : kInfinity, channel);
    if (const auto t = sample_collision(seg, channel, rng)) {
      const ChannelCoefficients c = coefficients(seg, *t, channel);
      // Absorbed (probability sigma_a / sigma_t), or out of scattering events.
      if (rng.next_float() * c.sigma_t >= c.sigma_s || volume_bounces >= limits.max_volume_bounces ||
          (!in_volume_run && surface_bounces + volume_runs >= limits.max_surface_bounces))
        break;
      radiance += throughput * medium_direct_light(scene, seg, *t, c.sigma_s, channel, rng);
      ray = Ray{ray.at(*t), sample_phase_mixture(seg, *t, c.sigma_s, channel, rng), 0.0f, kInfinity};
      ++volume_bounces;
      if (!in_volume_run) ++volume_runs;
      in_volume_run = true;
      direct = false;
      continue;
    }
    if (!hit) {
      if (direct) radiance += throughput * environment(scene, ray.direction)[channel];
      break;
    }
    const SurfaceInteraction si = scene.interaction(ray, *hit);
    const Vec3 wo = -ray.direction;
    if (direct) radiance += throughput * surface_emission(si, wo)[channel];
    const bool diffuse = std::visit(ScattersDiffusely{}, si.material->bsdf);
    if (!diffuse || surface_bounces + volume_runs >= limits.max_surface_bounces) break;
    radiance += throughput * surface_direct_light(scene, si, wo, channel, rng);
    const float u_lobe = rng.next_float();
    const auto bs = bsdf_sample(si.material->bsdf, si.ns, wo, u_lobe, next_2d(rng));
    if (!bs || dot(si.ng, bs->wi) * dot(si.ng, wo) <= 0.0f) break;
    throughput *= bs->weight[channel];
    ray = Ray{offset_ray_origin(si.p, si.ng, bs->wi), bs->wi, 0.0f, kInfinity};
    ++surface_bounces;
    in_volume_run = false;
    direct = false;
  }
  return in_channel(channel, 3.0f * radiance);
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
        const Ray ray = camera.generate_ray({float(x) + jitter.x, float(y) + jitter.y});
        const RGB v = options.estimator == ReferenceEstimator::kSingleScattering
                          ? reference_single_scattering(scene, ray, options.distance_samples, rng)
                          : reference_delta_tracking(scene, ray,
                                                     {options.max_bounces, options.max_surface_bounces}, rng);
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
