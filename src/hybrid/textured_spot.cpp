#include "hybrid/textured_spot.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "hybrid/scatter_pixels.h"
#include "media/phase.h"
#include "lights/light_profile.h"
#include "realtime/light_volume.h"
#include "realtime/scene_buffers.h"

namespace caligo {
namespace {

using scatter_pixels::pixel_noise;

GoboImage half_size(const GoboImage& src) {
  const int sw = src.width(), sh = src.height();
  const int w = std::max(sw / 2, 1), h = std::max(sh / 2, 1);
  std::vector<RGB> out(size_t(w) * size_t(h));
  for (int y = 0; y < h; ++y) {
    // Source rows [y0, y1) map to target row y: a partition of the source, so the mean is kept.
    const int y0 = y * sh / h, y1 = (y + 1) * sh / h;
    for (int x = 0; x < w; ++x) {
      const int x0 = x * sw / w, x1 = (x + 1) * sw / w;
      RGB sum(0.0f);
      for (int j = y0; j < y1; ++j)
        for (int i = x0; i < x1; ++i) sum += src.pixel(i, j);
      out[size_t(y) * size_t(w) + size_t(x)] = sum * (1.0f / float((x1 - x0) * (y1 - y0)));
    }
  }
  return GoboImage(w, h, std::move(out));
}

// The spot's emitted intensity towards a point (W/sr, no 1/d²), with the volumetric gobo at a
// mip level: the `blur_level` one, or a coarser one where a step's footprint asks for it.
struct Emitter {
  const SpotLight& light;
  std::vector<Gobo> levels;  // the light's gobo with each level of its mip chain (one: no image)
  int base = 0;              // the blur_level, clamped to the chain
  float tan_outer = 1.0f;
  float texels = 1.0f;       // the gobo's larger side

  // Towards p, for a step of length `step` along `dir` there: the level read is the one the
  // step's footprint asks for (at least `base`): the angle it subtends at the light over the
  // angle a texel spans (uv = 1/2 + tan / (2 tan_outer) about the axis), as log2.
  RGB towards(Vec3 p, Vec3 dir, float step) const {
    const Vec3 v = p - light.position;
    const float dist = length(v);
    if (!(dist > 0.0f)) return RGB(0.0f);
    const Vec3 w = v / dist;
    const float scale = spot_cone(light, w) * range_window(dist, light.range) * ies_factor(light.ies, w);
    if (!(scale > 0.0f)) return RGB(0.0f);
    int level = base;
    const float z = dot(w, light.direction);
    if (levels.size() > 1 && z > 1e-3f) {
      const float footprint = step * length(cross(dir, w)) / dist / (2.0f * tan_outer * z * z) * texels;
      if (footprint > 2.0f) level = std::max(base, int(std::log2(std::min(footprint, 0x1p30f))));  // not NaN
    }
    const Gobo& gobo = levels[size_t(std::min(level, int(levels.size()) - 1))];
    return light.intensity * gobo_filter(gobo, spot_gobo_uv(light, w)) * scale;
  }

  static Emitter make(const SpotLight& light, const TexturedSpotSettings& settings, const GoboMips* mips) {
    Emitter e{light, {light.gobo}};
    if (!light.gobo.image) return e;
    const float c = std::clamp(light.cos_outer, 1e-6f, 1.0f);
    e.tan_outer = std::max(std::sqrt(std::max(0.0f, 1.0f - c * c)) / c, 1e-6f);
    e.texels = float(std::max(light.gobo.image->width(), light.gobo.image->height()));
    const GoboMips own = mips ? GoboMips{} : gobo_mips(light.gobo.image);
    const GoboMips& chain = mips ? *mips : own;
    const int wanted = settings.blur_per_interval ? int(chain.size()) : std::max(settings.blur_level, 0) + 1;
    for (int k = 1; k < std::min(wanted, int(chain.size())); ++k) {
      e.levels.push_back(light.gobo);
      e.levels.back().image = chain[size_t(k)];
    }
    e.base = std::clamp(settings.blur_level, 0, int(e.levels.size()) - 1);
    return e;
  }
};

}  // namespace

std::vector<GoboImage> gobo_mip_chain(const GoboImage& image, int max_levels) {
  std::vector<GoboImage> chain{image};
  while (int(chain.size()) < max_levels && (chain.back().width() > 1 || chain.back().height() > 1))
    chain.push_back(half_size(chain.back()));
  return chain;
}

GoboMips gobo_mips(const std::shared_ptr<const GoboImage>& image) {
  GoboMips mips{image};
  if (!image) return mips;
  std::vector<GoboImage> chain = gobo_mip_chain(*image);
  for (size_t k = 1; k < chain.size(); ++k) mips.push_back(std::make_shared<const GoboImage>(std::move(chain[k])));
  return mips;
}

int textured_spot_steps(float abs_cos_axis, const TexturedSpotSettings& settings) {
  const int lo = std::max(settings.min_steps, 1), hi = std::max(settings.max_steps, lo);
  const float c = std::clamp(std::abs(abs_cos_axis), 0.0f, 1.0f);
  const float sin_a = std::sqrt(std::max(1.0f - c * c, 0.0f));
  // NaN direction reads as the transversal worst case.
  if (!(sin_a >= 0.0f)) return hi;
  return std::clamp(int(std::lround(float(lo) + float(hi - lo) * sin_a)), lo, hi);
}


namespace {

// Sun et al.'s closed form per step (airlight.h): consecutive steps share their endpoint tails,
// k + 1 tail evaluations per segment of k steps; exact in 1/d² and e^{-σ_t d} along the step.
struct AirlightSteps {
  const AirlightTable& table;
  AirlightRay air;
  float tail0 = 0.0f;

  void start(float a) { tail0 = airlight_tail(table, air, a); }
  // The step [t0, t1]'s radiance, E read at p; the tails advance whether or not it is lit.
  RGB step(float, float t1, Vec3 p, Vec3 dir, float length, float lit, const Emitter& emitter) {
    const float tail1 = airlight_tail(table, air, t1);
    const float weight = std::max(tail0 - tail1, 0.0f);
    tail0 = tail1;
    return lit > 0.0f ? emitter.towards(p, dir, length) * (lit * weight) : RGB(0.0f);
  }
};

// Hoffman and Preetham's per step (hoffman_preetham.h): the light at the midpoint, I e^{-σ_t d}
// / d², held over the step, any phase, every channel at once.
struct HoffmanPreethamSteps {
  const ScatteringMedium& medium;
  Vec3 light;
  bool grey = false;        // one exp per step for the light's leg, not three
  RGB transmittance{1.0f};  // e^{-σ_t t} at the step's start

  void start(float a) {
    const auto e = [&](int c) { return std::exp(-std::max(medium.sigma_t[c], 0.0f) * a); };
    transmittance = RGB(e(0), e(1), e(2));
  }
  RGB step(float t0, float t1, Vec3 p, Vec3 dir, float length, float lit, const Emitter& emitter) {
    const HoffmanPreethamStep s = hoffman_preetham_step(medium.sigma_t, transmittance, t1 - t0);
    transmittance = s.end;
    if (!(lit > 0.0f)) return RGB(0.0f);
    const Vec3 v = p - light;
    const float d2 = dot(v, v);
    if (!(d2 > 0.0f)) return RGB(0.0f);
    const float d = std::sqrt(d2);
    const auto leg = [&](int c) { return std::exp(-std::max(medium.sigma_t[c], 0.0f) * d); };
    const RGB attenuation = grey ? RGB(leg(0)) : RGB(leg(0), leg(1), leg(2));
    // The light travels along v / d before scattering and towards the eye (-dir) after.
    const float phase = phase_eval(medium.phase, v / d, -dir);
    const RGB irradiance = emitter.towards(p, dir, length) * attenuation * (lit / d2);
    return irradiance * medium.sigma_s * s.integral * phase;
  }
};

// The buffers must be the view's (a caller's bug otherwise, not bad input).
void check_buffers(const View& view, const Plane& opaque_depth, const ShadowVolumeBuffers* volumes) {
  if (opaque_depth.width != view.resolution.x || opaque_depth.height != view.resolution.y)
    throw std::invalid_argument("textured spot: opaque depth is " + std::to_string(opaque_depth.width) + "x" +
                                std::to_string(opaque_depth.height) + ", the view " +
                                std::to_string(view.resolution.x) + "x" + std::to_string(view.resolution.y));
  if (volumes && (volumes->front.width != opaque_depth.width || volumes->front.height != opaque_depth.height ||
                  volumes->tail_count.size() != opaque_depth.data.size()))
    throw std::invalid_argument("textured spot: shadow-volume buffers do not match the view");
}

// The pass with one step integrator: make_steps(origin, dir) gives a pixel's (AirlightSteps or
// HoffmanPreethamSteps). Everything but the per-step integral is shared.
template <typename MakeSteps>
ScatterResult march_spot(const View& view, const Plane& opaque_depth, const ShadowMap* shadow,
                         const SpotLight& light, const TexturedSpotSettings& settings,
                         const ShadowVolumeBuffers* volumes, const GoboMips* mips, const MakeSteps& make_steps) {
  check_buffers(view, opaque_depth, volumes);
  if (!shadow) volumes = nullptr;  // nothing casts a shadow: every step is lit
  const Emitter emitter = Emitter::make(light, settings, mips);
  const ShadedLight as_light{light};
  const float max_distance = std::max(settings.max_distance, 0.0f);
  const float jitter = std::clamp(settings.jitter, 0.0f, 1.0f), lit_rate = std::clamp(settings.lit_rate, 0.0f, 1.0f);
  const bool eye_lit = !volumes || volumes->eye_count == 0;

  return scatter_pixels::for_each_pixel(view, [&](int x, int y, int32_t& lookups) {
    const Ray ray = view.ray({float(x) + 0.5f, float(y) + 0.5f});
    const Vec3 o = ray.origin, dir = ray.direction;
    const float d = opaque_depth.at(x, y), per_t = view.depth_per_t(dir);
    // NaN depth reads as sky rather than poisoning the pixel.
    const float t_opaque = d < kSkyDepth && per_t > 0.0f ? std::max(d, 0.0f) / per_t : kInfinity;
    const float t_end = std::min(t_opaque, max_distance);
    const auto span = light_volume_interval(as_light, o, dir, 0.0f, t_end);
    if (!span || !(span->t1 > span->t0)) return RGB(0.0f);
    const float s0 = span->t0, s1 = span->t1;
    const int n = textured_spot_steps(dot(dir, light.direction), settings);
    auto steps_of = make_steps(o, dir);
    const float offset = 0.5f + jitter * (pixel_noise(x, y) - 0.5f);

    // [a, b] in `k` equal steps, E held per step, V read per step when `shadowed` (else 1).
    RGB sum(0.0f);
    const auto segment = [&](float a, float b, int k, bool shadowed) {
      if (!(b > a) || k <= 0) return;
      const float step = (b - a) / float(k);
      steps_of.start(a);
      for (int i = 0; i < k; ++i) {
        const float t0 = a + step * float(i), t1 = i + 1 == k ? b : a + step * float(i + 1);
        const Vec3 p = o + dir * (a + step * (float(i) + offset));
        const float lit = shadowed ? shadow->visibility(p) : 1.0f;
        sum += steps_of.step(t0, t1, p, dir, step, lit, emitter);
      }
      lookups += k;
    };
    // Steps over a part of the frustum stretch at a rate (1: the stretch's own, n per stretch).
    const auto steps = [&](float a, float b, float rate) {
      return b > a ? std::max(1, int(std::ceil(rate * float(n) * ((b - a) / (s1 - s0))))) : 0;
    };
    if (!volumes) {
      segment(s0, s1, n, shadow != nullptr);
    } else if (eye_lit && !volumes->covered(x, y)) {  // no shadow on this ray: the gobo alone
      segment(s0, s1, steps(s0, s1, lit_rate), false);
    } else {
      // Before the volumes: lit (eye outside every volume). Between them: the shadow map
      // decides. Beyond: lit when no volume holds the tail, dark otherwise.
      const float a = eye_lit ? std::clamp(volumes->front.at(x, y), s0, s1) : s0;
      const float b = std::clamp(volumes->back.at(x, y), a, s1);
      segment(s0, a, steps(s0, a, lit_rate), false);
      segment(a, b, steps(a, b, 1.0f), true);
      if (volumes->tail(x, y) == 0) segment(b, s1, steps(b, s1, lit_rate), false);
    }
    return sum;
  });
}

// Channel c of `from` into `into` (the other channels kept), lookups added.
void take_channel(ScatterResult& into, const ScatterResult& from, int c) {
  Plane* const planes[3] = {&into.radiance.r, &into.radiance.g, &into.radiance.b};
  const Plane* const source[3] = {&from.radiance.r, &from.radiance.g, &from.radiance.b};
  planes[c]->data = source[c]->data;
  for (size_t i = 0; i < into.lookups.size(); ++i) into.lookups[i] += from.lookups[i];
  into.total_lookups += from.total_lookups;
}

}  // namespace

ScatterResult scatter_textured_spot(const View& view, const Plane& opaque_depth, const ShadowMap* shadow,
                                    const AirlightTable& table, const AirlightMedium& medium,
                                    const SpotLight& light, const TexturedSpotSettings& settings,
                                    const ShadowVolumeBuffers* volumes, const GoboMips* mips) {
  return march_spot(view, opaque_depth, shadow, light, settings, volumes, mips, [&](Vec3 o, Vec3 dir) {
    return AirlightSteps{table, make_airlight_ray(table, medium, 1.0f, light.position, o, dir)};
  });
}

SpotScatterModel resolve_spot_model(SpotScatterModel model, const ScatteringMedium& medium) {
  if (model != SpotScatterModel::kAuto) return model;
  return medium.grey() && medium.isotropic() ? SpotScatterModel::kAirlight : SpotScatterModel::kHoffmanPreetham;
}

ScatterResult scatter_textured_spot(const View& view, const Plane& opaque_depth, const ShadowMap* shadow,
                                    const ScatteringMedium& medium, const SpotLight& light,
                                    const TexturedSpotSettings& settings, const ShadowVolumeBuffers* volumes,
                                    const GoboMips* mips) {
  if (resolve_spot_model(settings.model, medium) == SpotScatterModel::kHoffmanPreetham)
    return march_spot(view, opaque_depth, shadow, light, settings, volumes, mips,
                      [&](Vec3, Vec3) { return HoffmanPreethamSteps{medium, light.position, medium.grey()}; });
  if (!medium.isotropic())
    throw std::invalid_argument("textured spot: the airlight model takes an isotropic phase only");
  const AirlightTable& table = AirlightTable::shared();
  const auto pass = [&](int c) {
    return scatter_textured_spot(view, opaque_depth, shadow, table, AirlightMedium{medium.sigma_s[c], medium.sigma_t[c]},
                                 light, settings, volumes, mips);
  };
  ScatterResult result = pass(0);
  if (medium.grey()) return result;
  // A coloured medium: one pass per channel, each keeping its own channel.
  for (int c = 1; c < 3; ++c) take_channel(result, pass(c), c);
  result.marched_pixels = 0;
  for (int32_t n : result.lookups) result.marched_pixels += n > 0;
  return result;
}

}  // namespace caligo
