// Per-light accumulation (Glatzel 2014, "Accumulation pass"): march each low-resolution
// pixel ray inside the light's volume, clamped to the scene depth and to the media, and
// sum single scattering front to back:
//   L += sigma_s(p) p(theta) L_arrival(p) v(p) e^(-tau(light, p)) e^(-tau(camera, p)) dt.
// Unlike the seed we keep the phase function normalised over the sphere exactly as the
// path tracer does (phase_eval(phase, camera ray direction, direction to the light), see
// integrators/volume_direct.cpp), so the real-time frame converges to its reference.
#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include "lights/light_profile.h"
#include "realtime/accumulate_internal.h"
#include "realtime/light_volume.h"
#include "realtime/light_volume_simd.h"
#include "realtime/light_depth_volume.h"
#include "realtime/media.h"
#include "realtime/shadow_map.h"

namespace caligo {
namespace {

// Camera optical depth over [from, to] of the ray: every primitive's overlap with it. The march
// adds it step by step (steps go forwards), so a grid's quadrature covers the ray once, not
// once per step from the start.
RGB camera_optical_depth(const VolumeScene& volumes, const PixelMarch& march, float from, float to) {
  const Ray ray{march.origin, march.dir, 0.0f, kInfinity};
  RGB tau;
  for (const VolumeInterval& iv : march.intervals) {
    const float a = std::max(from, iv.t0), b = std::min(to, iv.t1);
    if (b > a) tau += primitive_optical_depth(volumes.primitive(iv.primitive), ray, a, b);
  }
  return tau;
}

constexpr int kLanes = int(LightVolumeLanes::Batch::size);

// The light-volume spans of pixels x0 .. x0 + n - 1 of row y (n <= kLanes), tested 8 at a
// time in float, with the scalar light_volume_interval where float is unsure.
struct PixelSpans {
  bool hit[kLanes];
  RayRange span[kLanes];
};

bool light_spans(const LightVolumeLanes& lanes, const ShadedLight& light, const AccumulationRays& rays, int x0,
                 int y, int n, PixelSpans& out) {
  using Batch = LightVolumeLanes::Batch;
  alignas(32) float v[7][kLanes];
  bool any = false;
  for (int i = 0; i < kLanes; ++i) {
    const AccumulationRays::PixelRay* ray = i < n ? &rays.pixel(x0 + i, y) : nullptr;
    // Rays without media (or past the row's end) get an empty span: tmax < 0.
    const bool live = ray && ray->count > 0;
    any = any || live;
    const Vec3 o = live ? ray->origin : Vec3(0.0f), d = live ? ray->dir : Vec3(0.0f, 0.0f, 1.0f);
    v[0][i] = o.x, v[1][i] = o.y, v[2][i] = o.z;
    v[3][i] = d.x, v[4][i] = d.y, v[5][i] = d.z;
    v[6][i] = live ? ray->t_end : -1.0f;
  }
  if (!any) return false;
  const LightVolumeLanes::Result r =
      lanes.intervals({Batch::load_aligned(v[0]), Batch::load_aligned(v[1]), Batch::load_aligned(v[2]),
                       Batch::load_aligned(v[3]), Batch::load_aligned(v[4]), Batch::load_aligned(v[5]),
                       Batch::load_aligned(v[6])});
  alignas(32) float t0[kLanes], t1[kLanes], hit[kLanes], unsure[kLanes];
  r.t0.store_aligned(t0);
  r.t1.store_aligned(t1);
  xsimd::select(r.hit, Batch(1.0f), Batch(0.0f)).store_aligned(hit);
  xsimd::select(r.unsure, Batch(1.0f), Batch(0.0f)).store_aligned(unsure);
  any = false;
  for (int i = 0; i < n; ++i) {
    out.hit[i] = v[6][i] > 0.0f && (unsure[i] != 0.0f || hit[i] != 0.0f);
    if (!out.hit[i]) continue;
    out.span[i] = {t0[i], t1[i]};
    if (unsure[i] != 0.0f) {
      const Vec3 o(v[0][i], v[1][i], v[2][i]), d(v[3][i], v[4][i], v[5][i]);
      const auto exact = light_volume_interval(light, o, d, 0.0f, v[6][i]);
      out.hit[i] = exact.has_value();
      if (exact) out.span[i] = *exact;
    }
    any = any || out.hit[i];
  }
  return any;
}

}  // namespace

float media_extent(const VolumeScene& volumes) {
  Bounds3 b;
  for (const VolumePrimitive& p : volumes.primitives()) b.extend(volume_bounds(p.shape));
  return b.empty() ? 0.0f : length(b.diagonal()) * 1.01f + 1e-3f;
}

const Vec3* equiangular_focus(const ShadedLight& light) {
  // Exhaustive, so that a new light type has to say whether its steps crowd towards a point.
  struct Focus {
    const Vec3* operator()(const PointLight& l) const { return &l.position; }
    const Vec3* operator()(const SpotLight& l) const { return &l.position; }
    const Vec3* operator()(const BoxLight&) const { return nullptr; }  // parallel light: no 1/d^2
    const Vec3* operator()(const DirectionalLight&) const { return nullptr; }
  };
  return std::visit(Focus{}, light);
}

bool setup_pixel_march(RayRange span, const AccumulationRays::PixelRay& ray,
                       std::span<const VolumeInterval> intervals, const AccumulationSettings& settings,
                       PixelMarch& march, const Vec3* focus) {
  // Clamped to the extent of the media on the ray (the light volume is convex, so clipping
  // its interval is the same as intersecting the volumes).
  const float t0 = std::max(ray.media_t0, span.t0);
  const float t1 = std::min(ray.media_t1, span.t1);
  if (!(t1 > t0)) return false;
  march.origin = ray.origin;
  march.dir = ray.dir;
  march.t0 = t0;
  march.samples = std::max(1, settings.samples);
  march.step = (t1 - t0) / float(march.samples);
  march.offset = ray.offset;
  march.intervals = intervals;
  march.equiangular = false;
  if (focus) {
    const float tc = dot(*focus - ray.origin, ray.dir);
    const float d = length(ray.origin + ray.dir * tc - *focus);
    // A ray through the light itself has no finite angle range: uniform steps then.
    if (d > 1e-6f * (t1 - t0)) {
      march.equiangular = true;
      march.tc = tc;
      march.D = d;
      march.theta0 = std::atan2(t0 - tc, d);
      march.dtheta = (std::atan2(t1 - tc, d) - march.theta0) / float(march.samples);
    }
  }
  return true;
}

namespace {

// The transmittance from p to the light: the grids' from the light's table where it has one,
// the other primitives' integrated.
RGB light_transmittance(const FrameLight& light, const VolumeScene& volumes, Vec3 p, Vec3 light_point) {
  const LightDepthVolume* table = light.media_depth;
  if (!table) return exp_neg(segment_optical_depth(volumes, p, light_point));
  const float len = distance(p, light_point);
  if (!(len > 0.0f)) return RGB(1.0f);
  const Ray ray{p, (light_point - p) / len, 0.0f, len};
  RGB tau;
  for (size_t i = 0; i < volumes.primitives().size(); ++i)
    if (!table->holds(i)) tau += primitive_segment_optical_depth(volumes.primitives()[i], ray);
  return table->transmittance(p) * exp_neg(tau);
}

}  // namespace

RGB inscatter_scalar(const FrameLight& light, const VolumeScene& volumes, const PixelMarch& march, float t,
                     float multiple_scattering_floor, float far) {
  const Vec3 p = march.origin + march.dir * t;
  const auto arrival = std::visit([&](const auto& l) { return delta_arrival(l, p); }, light.light);
  if (!arrival) return {};
  // sigma_s x phase summed over the primitives here: overlapping media add their
  // coefficients and mix their phase functions in proportion to sigma_s.
  RGB scatter;
  for (const VolumeInterval& iv : march.intervals) {
    if (t < iv.t0 || t > iv.t1) continue;
    const VolumePrimitive& prim = volumes.primitive(iv.primitive);
    scatter += prim.shader.sigma_s * (medium_density(prim, p) * phase_eval(prim.shader.phase, march.dir, arrival->wi));
  }
  if (scatter.is_black()) return {};
  const float v = light.shadow ? std::max(multiple_scattering_floor, light.shadow->visibility(p)) : 1.0f;
  if (!(v > 0.0f)) return {};
  const Vec3 light_point = p + arrival->wi * std::min(arrival->distance, far);
  return scatter * arrival->radiance * light_transmittance(light, volumes, p, light_point) * v;
}

RGB march_scalar(const FrameLight& light, const VolumeScene& volumes, const PixelMarch& march,
                 float multiple_scattering_floor, float far) {
  RGB sum, tau;
  float reached = 0.0f;  // tau is the camera optical depth to here
  for (int k = 0; k < march.samples; ++k) {
    float weight;
    const float t = march_sample(march, float(k), weight);
    const RGB in = inscatter_scalar(light, volumes, march, t, multiple_scattering_floor, far);
    if (in.is_black()) continue;
    tau += camera_optical_depth(volumes, march, reached, t);
    reached = std::max(reached, t);
    sum += in * exp_neg(tau) * weight;
  }
  return sum;
}

void accumulate_light(const FrameLight& light, const VolumeScene& volumes, const AccumulationRays& rays,
                      const AccumulationSettings& settings, ColorPlanes& accum) {
  if (!light.options.volumetric || volumes.empty()) return;
  const float far = media_extent(volumes);
  SimdMarcher simd(light, volumes, settings.multiple_scattering_floor, far);
  const bool use_simd = settings.simd && simd.supported();
  const float intensity = light.options.volumetric_intensity;
  const PixelRect rect = light_screen_bounds(light.light, rays.view());
  const LightVolumeLanes light_volume(light.light);
  const Vec3* focus = settings.equiangular ? equiangular_focus(light.light) : nullptr;
  // Square tiles rather than rows: neighbouring rays sample neighbouring shadow-map texels,
  // gobo texels and noise cells, and a tile's samples stay in cache where a row's do not.
  constexpr int kTile = 16;
  const int tiles_x = (std::max(0, rect.x1 - rect.x0) + kTile - 1) / kTile;
  const int tiles_y = (std::max(0, rect.y1 - rect.y0) + kTile - 1) / kTile;
  parallel_for(tiles_x * tiles_y, [&](int tile) {
    const int tx0 = rect.x0 + (tile % tiles_x) * kTile, ty0 = rect.y0 + (tile / tiles_x) * kTile;
    const int x_end = std::min(tx0 + kTile, rect.x1), y_end = std::min(ty0 + kTile, rect.y1);
    // Pixels are set up kLead ahead of the one being marched, and the SIMD marcher prefetches
    // their shadow-map texels at setup, so the scattered texel loads overlap earlier marches.
    // 2 to 4 measured alike on the arena's 2048^2 sun map; 8 was slower (the prefetched
    // lines start evicting each other).
    constexpr int kLead = 4;
    PixelMarch queue[kLead];
    int queue_x[kLead], queue_y[kLead];
    int queued = 0;
    auto flush = [&](int slot) {
      const PixelMarch& march = queue[slot];
      const RGB l = use_simd ? simd.march(march)
                             : march_scalar(light, volumes, march, settings.multiple_scattering_floor, far);
      const int x = queue_x[slot], y = queue_y[slot];
      accum.r.at(x, y) += l.r * intensity;
      accum.g.at(x, y) += l.g * intensity;
      accum.b.at(x, y) += l.b * intensity;
    };
    PixelSpans spans;
    for (int y = ty0; y < y_end; ++y) {
      for (int x0 = tx0; x0 < x_end; x0 += kLanes) {
        const int n = std::min(kLanes, x_end - x0);
        if (!light_spans(light_volume, light.light, rays, x0, y, n, spans)) continue;
        for (int i = 0; i < n; ++i) {
          if (!spans.hit[i]) continue;
          const int x = x0 + i;
          const AccumulationRays::PixelRay& ray = rays.pixel(x, y);
          PixelMarch march;
          if (!setup_pixel_march(spans.span[i], ray, rays.intervals(y, ray), settings, march, focus)) continue;
          const int slot = queued % kLead;
          if (queued >= kLead) flush(slot);
          queue[slot] = march;
          queue_x[slot] = x;
          queue_y[slot] = y;
          if (use_simd) simd.prefetch(march);
          ++queued;
        }
      }
    }
    for (int q = std::max(0, queued - kLead); q < queued; ++q) flush(q % kLead);
  });
}

void accumulate_light(const FrameLight& light, const VolumeScene& volumes, const View& view,
                      const Plane& depth, const AccumulationSettings& settings, ColorPlanes& accum) {
  if (!light.options.volumetric || volumes.empty()) return;
  accumulate_light(light, volumes, AccumulationRays(volumes, view, depth, settings), settings, accum);
}

}  // namespace caligo
