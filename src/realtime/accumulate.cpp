// Per-light accumulation (Glatzel 2014, "Accumulation pass"): march each low-resolution
// pixel ray inside the light's volume, clamped to the scene depth and to the media, and
// sum single scattering front to back:
//   L += sigma_s(p) p(theta) L_arrival(p) v(p) e^(-tau(light, p)) e^(-tau(camera, p)) dt.
// Unlike the seed we keep the phase function normalised over the sphere exactly as the
// path tracer does (phase_eval(phase, camera ray direction, direction to the light), see
// integrators/volume_direct.cpp), so the real-time frame converges to its reference.
#include <algorithm>
#include <cmath>
#include <atomic>
#include <cstdio>
#include <cstdlib>

#include "core/parallel.h"
#include "lights/light_profile.h"
#include "realtime/accumulate_internal.h"
#include "realtime/light_volume.h"
#include "realtime/media.h"
#include "realtime/shadow_map.h"

namespace caligo {
namespace {

// Delta arrival of the light types the passes march; directional lights are parallel.
struct Arrival {
  Vec3 receiver;
  std::optional<DeltaArrival> operator()(const PointLight& l) const { return delta_arrival(l, receiver); }
  std::optional<DeltaArrival> operator()(const SpotLight& l) const { return delta_arrival(l, receiver); }
  std::optional<DeltaArrival> operator()(const BoxLight& l) const { return delta_arrival(l, receiver); }
  std::optional<DeltaArrival> operator()(const DirectionalLight& l) const {
    return DeltaArrival{l.irradiance, -l.direction, kInfinity};
  }
  std::optional<DeltaArrival> operator()(const SphereLight&) const { return std::nullopt; }
  std::optional<DeltaArrival> operator()(const QuadLight&) const { return std::nullopt; }
  std::optional<DeltaArrival> operator()(const TriangleLight&) const { return std::nullopt; }
  std::optional<DeltaArrival> operator()(const EnvironmentLight&) const { return std::nullopt; }
};

// Camera optical depth from the start of the ray to t: every primitive's overlap with [0, t].
RGB camera_optical_depth(const VolumeScene& volumes, const PixelMarch& march, float t) {
  const Ray ray{march.origin, march.dir, 0.0f, kInfinity};
  RGB tau;
  for (const VolumeInterval& iv : march.intervals)
    if (t > iv.t0)
      tau += primitive_optical_depth(volumes.primitive(iv.primitive), ray, iv.t0, std::min(t, iv.t1));
  return tau;
}

RGB exp_neg(RGB tau) { return {std::exp(-tau.r), std::exp(-tau.g), std::exp(-tau.b)}; }

}  // namespace

float media_extent(const VolumeScene& volumes) {
  Bounds3 b;
  for (const VolumePrimitive& p : volumes.primitives()) b.extend(volume_bounds(p.shape));
  return b.empty() ? 0.0f : length(b.diagonal()) * 1.01f + 1e-3f;
}

bool setup_pixel_march(const Light& light, const AccumulationRays::PixelRay& ray,
                       std::span<const VolumeInterval> intervals, const AccumulationSettings& settings,
                       PixelMarch& march) {
  if (intervals.empty()) return false;
  const auto span = light_volume_interval(light, ray.origin, ray.dir, 0.0f, ray.t_end);
  if (!span) return false;
  // Clamped to the extent of the media on the ray (the light volume is convex, so clipping
  // its interval is the same as intersecting the volumes).
  const float t0 = std::max(ray.media_t0, span->t0);
  const float t1 = std::min(ray.media_t1, span->t1);
  if (!(t1 > t0)) return false;
  march.origin = ray.origin;
  march.dir = ray.dir;
  march.t0 = t0;
  march.samples = std::max(1, settings.samples);
  march.step = (t1 - t0) / float(march.samples);
  march.offset = ray.offset;
  march.intervals = intervals;
  return true;
}

RGB march_scalar(const FrameLight& light, const VolumeScene& volumes, const PixelMarch& march,
                 float multiple_scattering_floor, float far) {
  RGB sum;
  for (int k = 0; k < march.samples; ++k) {
    const float t = march.t0 + (float(k) + march.offset) * march.step;
    const Vec3 p = march.origin + march.dir * t;
    const auto arrival = std::visit(Arrival{p}, light.light);
    if (!arrival) continue;
    // sigma_s x phase summed over the primitives here: overlapping media add their
    // coefficients and mix their phase functions in proportion to sigma_s.
    RGB scatter;
    for (const VolumeInterval& iv : march.intervals) {
      if (t < iv.t0 || t > iv.t1) continue;
      const VolumePrimitive& prim = volumes.primitive(iv.primitive);
      scatter += prim.shader.sigma_s *
                 (medium_density(prim, p) * phase_eval(prim.shader.phase, march.dir, arrival->wi));
    }
    if (scatter.is_black()) continue;
    const float v = light.shadow ? std::max(multiple_scattering_floor, light.shadow->visibility(p)) : 1.0f;
    if (!(v > 0.0f)) continue;
    const Vec3 light_point = p + arrival->wi * std::min(arrival->distance, far);
    const RGB tau = camera_optical_depth(volumes, march, t) + segment_optical_depth(volumes, p, light_point);
    sum += scatter * arrival->radiance * exp_neg(tau) * v;
  }
  return sum * march.step;
}

void accumulate_light(const FrameLight& light, const VolumeScene& volumes, const AccumulationRays& rays,
                      const AccumulationSettings& settings, ColorPlanes& accum) {
  if (!light.options.volumetric || volumes.empty()) return;
  const float far = media_extent(volumes);
  SimdMarcher simd(light, volumes, settings.multiple_scattering_floor, far);
  const bool use_simd = settings.simd && simd.supported();
  const float intensity = light.options.volumetric_intensity;
  const PixelRect rect = light_screen_bounds(light.light, rays.view());
  // Square tiles rather than rows: neighbouring rays sample neighbouring shadow-map texels,
  // gobo texels and noise cells, and a tile's samples stay in cache where a row's do not.
  constexpr int kTile = 16;
  const int tiles_x = (std::max(0, rect.x1 - rect.x0) + kTile - 1) / kTile;
  const int tiles_y = (std::max(0, rect.y1 - rect.y0) + kTile - 1) / kTile;
  static std::atomic<long> stat_rect{0}, stat_marched{0};
  stat_rect += long(std::max(0, rect.x1 - rect.x0)) * std::max(0, rect.y1 - rect.y0);
  parallel_for(tiles_x * tiles_y, [&](int tile) {
    const int tx0 = rect.x0 + (tile % tiles_x) * kTile, ty0 = rect.y0 + (tile / tiles_x) * kTile;
    const int x_end = std::min(tx0 + kTile, rect.x1), y_end = std::min(ty0 + kTile, rect.y1);
    // Set up one pixel ahead of the one being marched, and let the SIMD marcher prefetch
    // the next pixel's shadow-map texels while this one computes.
    PixelMarch marches[2];
    int pending_x = -1, pending_y = -1;
    auto flush = [&](const PixelMarch& march) {
      const RGB l = use_simd ? simd.march(march)
                             : march_scalar(light, volumes, march, settings.multiple_scattering_floor, far);
      accum.r.at(pending_x, pending_y) += l.r * intensity;
      accum.g.at(pending_x, pending_y) += l.g * intensity;
      accum.b.at(pending_x, pending_y) += l.b * intensity;
    };
    int slot = 0;
    for (int y = ty0; y < y_end; ++y) {
      for (int x = tx0; x < x_end; ++x) {
        const AccumulationRays::PixelRay& ray = rays.pixel(x, y);
        PixelMarch& next = marches[slot];
        if (!setup_pixel_march(light.light, ray, rays.intervals(y, ray), settings, next)) continue;
        stat_marched++;
        if (use_simd) simd.prefetch(next);
        if (pending_x >= 0) flush(marches[1 - slot]);
        pending_x = x;
        pending_y = y;
        slot = 1 - slot;
      }
    }
    if (pending_x >= 0) flush(marches[1 - slot]);
  });
  if (getenv("ACC_STATS")) fprintf(stderr, "rect %ld marched %ld\n", stat_rect.exchange(0), stat_marched.exchange(0));
}

void print_stats_now() {}
void accumulate_light(const FrameLight& light, const VolumeScene& volumes, const View& view,
                      const Plane& depth, const AccumulationSettings& settings, ColorPlanes& accum) {
  if (!light.options.volumetric || volumes.empty()) return;
  accumulate_light(light, volumes, AccumulationRays(volumes, view, depth, settings), settings, accum);
}

}  // namespace caligo
