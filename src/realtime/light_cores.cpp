#include "realtime/light_cores.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include "realtime/accumulate_internal.h"
#include "realtime/light_volume.h"

namespace caligo {
namespace {

// The output pixels within `radius` of a marched light's focus in front of the camera, each once
// with its distance to the nearest focus.
std::vector<DiscPixel> core_pixels(const std::vector<FrameLight>& lights, const View& view, float radius) {
  const Vec2i res = view.resolution;
  std::vector<int32_t> index(size_t(res.x) * size_t(res.y), -1);
  std::vector<DiscPixel> pixels;
  for (const FrameLight& light : lights) {
    const Vec3* focus = light.options.volumetric ? equiangular_focus(light.light) : nullptr;
    if (!focus) continue;
    for (const DiscPixel& d : disc_pixels(res, view.project(*focus), radius)) {
      int32_t& i = index[size_t(d.pixel.y) * size_t(res.x) + size_t(d.pixel.x)];
      if (i >= 0) {
        pixels[size_t(i)].distance = std::min(pixels[size_t(i)].distance, d.distance);
        continue;
      }
      i = int32_t(pixels.size());
      pixels.push_back(d);
    }
  }
  return pixels;
}

// Every marched light's in-scattering along one ray (the accumulation pass's march, scalar).
RGB march_all(const std::vector<FrameLight>& lights, const VolumeScene& volumes, const Ray& ray, float t_end,
              const AccumulationSettings& settings, float far, VolumeContext& context) {
  volumes.intervals(Ray{ray.origin, ray.direction, 0.0f, t_end}, context);
  AccumulationRays::PixelRay pixel;
  pixel.origin = ray.origin;
  pixel.dir = ray.direction;
  pixel.t_end = t_end;
  pixel.media_t0 = kInfinity;
  pixel.media_t1 = -kInfinity;
  for (const VolumeInterval& iv : context.intervals) {
    pixel.media_t0 = std::min(pixel.media_t0, iv.t0);
    pixel.media_t1 = std::max(pixel.media_t1, iv.t1);
  }
  RGB sum;
  for (const FrameLight& light : lights) {
    if (!light.options.volumetric) continue;
    const auto span = light_volume_interval(light.light, ray.origin, ray.direction, 0.0f, t_end);
    if (!span) continue;
    PixelMarch march;
    if (!setup_pixel_march(*span, pixel, context.intervals, settings, march, equiangular_focus(light.light))) continue;
    sum += march_scalar(light, volumes, march, settings.multiple_scattering_floor, far) *
           light.options.volumetric_intensity;
  }
  return sum;
}

}  // namespace

std::vector<DiscPixel> disc_pixels(Vec2i res, Vec3 p, float radius) {
  std::vector<DiscPixel> out;
  if (!(p.z > 0.0f) || !std::isfinite(p.x) || !std::isfinite(p.y)) return out;
  const int x0 = std::max(0, int(std::floor(p.x - radius))), x1 = std::min(res.x - 1, int(std::ceil(p.x + radius)));
  const int y0 = std::max(0, int(std::floor(p.y - radius))), y1 = std::min(res.y - 1, int(std::ceil(p.y + radius)));
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const float dx = float(x) + 0.5f - p.x, dy = float(y) + 0.5f - p.y;
      const float r = std::sqrt(dx * dx + dy * dy);
      if (r <= radius) out.push_back({{x, y}, r});
    }
  return out;
}

int resolve_light_cores(const std::vector<FrameLight>& lights, const VolumeScene& volumes, const View& view,
                        const Plane& depth, const AccumulationSettings& accumulation,
                        const LightCoreSettings& settings, ColorPlanes& volumetric) {
  if (volumes.empty()) return 0;
  const std::vector<DiscPixel> pixels = core_pixels(lights, view, settings.radius);
  if (pixels.empty()) return 0;
  AccumulationSettings march = accumulation;
  march.samples = std::max(1, settings.samples);
  const float far = media_extent(volumes);
  parallel_for(int(pixels.size()), [&](int i) {
    thread_local VolumeContext context;
    const Vec2i px = pixels[size_t(i)].pixel;
    // The peak varies within a pixel only next to the light: subpixels^2 rays within 2 pixels of
    // it, 2 x 2 within 6, one ray beyond.
    const float r = pixels[size_t(i)].distance;
    const int n = r <= 2.0f ? std::max(1, settings.subpixels) : (r <= 6.0f ? 2 : 1);
    const float d = depth.at(px.x, px.y);
    RGB sum;
    for (int sy = 0; sy < n; ++sy)
      for (int sx = 0; sx < n; ++sx) {
        const Ray ray = view.ray({float(px.x) + (float(sx) + 0.5f) / float(n), float(px.y) + (float(sy) + 0.5f) / float(n)});
        const float per_t = view.depth_per_t(ray.direction);
        if (!(per_t > 0.0f)) continue;
        sum += march_all(lights, volumes, ray, std::max(d, 0.0f) / per_t, march, far, context);
      }
    sum *= 1.0f / float(n * n);
    volumetric.r.at(px.x, px.y) = sum.r;
    volumetric.g.at(px.x, px.y) = sum.g;
    volumetric.b.at(px.x, px.y) = sum.b;
  });
  return int(pixels.size());
}

}  // namespace caligo
