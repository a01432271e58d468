#include "hybrid/hybrid_scatter.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "hybrid/scatter_pixels.h"
#include "realtime/scene_buffers.h"

namespace caligo {
namespace {

void check_size(const Plane& plane, const View& view, const char* what) {
  if (plane.width != view.resolution.x || plane.height != view.resolution.y)
    throw std::invalid_argument(std::string("hybrid scatter: ") + what + " is " +
                                std::to_string(plane.width) + "x" + std::to_string(plane.height) +
                                ", the view " + std::to_string(view.resolution.x) + "x" +
                                std::to_string(view.resolution.y));
}

using scatter_pixels::for_each_pixel;
using scatter_pixels::pixel_noise;

// The airlight of one light for one frame: the per-frame table where it is accurate (and
// asked for; it needs one eye for every pixel: a perspective view), else the closed form's table.
struct FrameSource {
  const AirlightTable& table;
  std::optional<FrameAirlight> frame;
  FrameSource(const AirlightTable& t, const AirlightMedium& medium, const HybridLight& light, const View& view,
              const HybridSettings& settings)
      : table(t) {
    if (settings.frame_table && view.projection == Projection::perspective &&
        std::max(medium.sigma_t, 0.0f) * length(light.position - view.eye) <= kFrameTableMaxDepth)
      frame.emplace(t, medium, light.intensity, light.position, view.eye);
  }
};

struct PixelRay {
  Ray ray;
  AirlightRay air;             // without a frame table
  FrameAirlight::Ray framed;   // with one
  const FrameSource* source = nullptr;
  float t_opaque = kInfinity;  // the visible surface (kInfinity for the sky)
  float t_end = 0.0f;          // where marching stops: min(t_opaque, max_distance)
  float offset = 0.5f;         // visibility sample position inside a step, in steps
};

// L(t0, t1) of the pixel's ray, by whichever form its frame uses.
float lit(const PixelRay& p, float t0, float t1) {
  return p.source->frame ? p.source->frame->interval(p.framed, t0, t1) : airlight_interval(p.source->table, p.air, t0, t1);
}

PixelRay pixel_ray(const View& view, const Plane& depth, int x, int y, const FrameSource& source,
                   const AirlightMedium& medium, const HybridLight& light, const HybridSettings& settings) {
  PixelRay p;
  p.ray = view.ray({float(x) + 0.5f, float(y) + 0.5f});
  const float d = depth.at(x, y), per_t = view.depth_per_t(p.ray.direction);
  // NaN depth reads as sky rather than poisoning the pixel.
  p.t_opaque = d < kSkyDepth && per_t > 0.0f ? std::max(d, 0.0f) / per_t : kInfinity;
  p.t_end = std::min(p.t_opaque, std::max(settings.max_distance, 0.0f));
  const float jitter = std::clamp(settings.jitter, 0.0f, 1.0f);
  p.offset = 0.5f + jitter * (pixel_noise(x, y) - 0.5f);
  p.source = &source;
  if (source.frame)
    p.framed = source.frame->ray(p.ray.direction);
  else
    p.air = make_airlight_ray(source.table, medium, light.intensity, light.position, p.ray.origin, p.ray.direction);
  return p;
}

// Visibility is read once per step of [a, b]; each maximal lit run of steps is integrated in
// closed form. A run may come in lit from `run_from` (< 0: it does not). When the ray is known
// to be lit beyond b up to `lit_until` (> b; <= b: shadowed or nothing there) the last run goes
// on to it, or one starts at b: a ray may leave the shadow exactly at b with every step dark.
float march(const ShadowMap& shadow, const PixelRay& p, float a, float b, int n, float run_from, float lit_until,
            int32_t& lookups) {
  const Vec3 o = p.ray.origin, dir = p.ray.direction;
  const float step = (b - a) / float(n);
  float sum = 0.0f;
  for (int i = 0; i < n; ++i) {
    const float t0 = a + step * float(i);
    const float ts = a + step * (float(i) + p.offset);
    const bool visible = shadow.visibility(o + dir * ts) > 0.5f;
    if (visible && run_from < 0.0f) run_from = t0;
    if (!visible && run_from >= 0.0f) {
      sum += lit(p, run_from, t0);
      run_from = -1.0f;
    }
  }
  lookups += n;
  if (lit_until > b) {
    sum += lit(p, run_from >= 0.0f ? run_from : b, lit_until);
  } else if (run_from >= 0.0f) {
    sum += lit(p, run_from, b);
  }
  return sum;
}

}  // namespace

ScatterResult scatter_brute(const View& view, const Plane& opaque_depth, const ShadowMap& shadow,
                            const AirlightTable& table, const AirlightMedium& medium,
                            const HybridLight& light, const HybridSettings& settings) {
  check_size(opaque_depth, view, "opaque depth");
  const int n = std::max(settings.brute_samples, 1);
  const FrameSource source(table, medium, light, view, settings);
  return for_each_pixel(view, [&](int x, int y, int32_t& lookups) {
    const PixelRay p = pixel_ray(view, opaque_depth, x, y, source, medium, light, settings);
    // Beyond t_end (max_distance) the ray counts as lit: [t_end, t_opaque] joins the last run.
    return light.color * march(shadow, p, 0.0f, p.t_end, n, -1.0f, p.t_opaque, lookups);
  });
}

ScatterResult scatter_hybrid(const View& view, const Plane& opaque_depth, const ShadowVolumeBuffers& volumes,
                             const ShadowMap& shadow, const AirlightTable& table,
                             const AirlightMedium& medium, const HybridLight& light,
                             const HybridSettings& settings) {
  check_size(opaque_depth, view, "opaque depth");
  check_size(volumes.front, view, "shadow-volume front");
  check_size(volumes.back, view, "shadow-volume back");
  if (volumes.tail_count.size() != opaque_depth.data.size())
    throw std::invalid_argument("hybrid scatter: shadow-volume tail counts do not match the view");
  const int n = std::max(settings.samples, 1);
  const bool eye_lit = volumes.eye_count == 0;
  const FrameSource source(table, medium, light, view, settings);
  return for_each_pixel(view, [&](int x, int y, int32_t& lookups) {
    const PixelRay p = pixel_ray(view, opaque_depth, x, y, source, medium, light, settings);
    if (eye_lit && !volumes.covered(x, y)) return light.color * lit(p, 0.0f, p.t_opaque);
    // The buffers hold t along the same unit ray; clamp them into the marched range.
    const float a = eye_lit ? std::clamp(volumes.front.at(x, y), 0.0f, p.t_end) : 0.0f;
    const bool tail_lit = volumes.tail(x, y) == 0;
    const float b = settings.conservative_tails && !tail_lit ? p.t_end : std::clamp(volumes.back.at(x, y), a, p.t_end);
    // Beyond b: lit to the surface when no volume holds the tail (or b is already t_end, beyond
    // which the ray counts as lit); else shadowed up to t_end and lit after it.
    float extra = 0.0f;
    float lit_until = b;
    if (b >= p.t_end || tail_lit) {
      lit_until = p.t_opaque;
    } else if (p.t_opaque > p.t_end) {
      extra = lit(p, p.t_end, p.t_opaque);
    }
    return light.color * (march(shadow, p, a, b, n, eye_lit ? 0.0f : -1.0f, lit_until, lookups) + extra);
  });
}

ColorPlanes scatter_unshadowed(const View& view, const Plane& opaque_depth, const AirlightTable& table,
                               const AirlightMedium& medium, const HybridLight& light,
                               const HybridSettings& settings) {
  check_size(opaque_depth, view, "opaque depth");
  const FrameSource source(table, medium, light, view, settings);
  return for_each_pixel(view,
                        [&](int x, int y, int32_t&) {
                          const PixelRay p = pixel_ray(view, opaque_depth, x, y, source, medium, light, settings);
                          return light.color * lit(p, 0.0f, p.t_opaque);
                        })
      .radiance;
}

}  // namespace caligo
