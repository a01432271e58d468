#include "realtime/light_volume.h"

#include <algorithm>
#include <cmath>
#include <vector>


namespace caligo {

namespace {

// Corners whose convex hull contains the light's volume; empty for unbounded volumes.
struct VolumeCorners {
  std::vector<Vec3>& out;
  void box(Vec3 c, Vec3 a, Vec3 b, Vec3 d) const {  // c +- a +- b +- d
    for (int i = 0; i < 8; ++i)
      out.push_back(c + a * (i & 1 ? 1.0f : -1.0f) + b * (i & 2 ? 1.0f : -1.0f) + d * (i & 4 ? 1.0f : -1.0f));
  }
  void sphere(Vec3 c, float r) const { box(c, {r, 0, 0}, {0, r, 0}, {0, 0, r}); }
  void operator()(const PointLight& l) const {
    if (std::isfinite(l.range)) sphere(l.position, l.range);
  }
  void operator()(const SpotLight& l) const {
    if (!std::isfinite(l.range)) return;
    // Narrow cones: the apex and the square around the cone's section at axial distance
    // `range` (the cone cut by the range sphere lies within that truncated cone).
    if (l.cos_outer < 0.5f) return sphere(l.position, l.range);
    const float r = l.range * std::sqrt(1.0f - l.cos_outer * l.cos_outer) / l.cos_outer;
    const Frame f = Frame::from_z(l.direction);
    out.push_back(l.position);
    for (int i = 0; i < 4; ++i)
      out.push_back(l.position + l.direction * l.range + f.s * (i & 1 ? r : -r) + f.t * (i & 2 ? r : -r));
  }
  void operator()(const BoxLight& l) const {
    const Vec3 right = cross(l.direction, l.up);
    box(l.position + l.direction * (0.5f * l.range), right * l.half_width, l.up * l.half_height,
        l.direction * (0.5f * l.range));
  }
  void operator()(const DirectionalLight&) const {}
};

}  // namespace

PixelRect light_screen_bounds(const ShadedLight& light, const View& view) {
  const PixelRect all{0, 0, view.resolution.x, view.resolution.y};
  std::vector<Vec3> corners;
  std::visit(VolumeCorners{corners}, light);
  if (corners.empty()) return all;
  float x0 = kInfinity, y0 = kInfinity, x1 = -kInfinity, y1 = -kInfinity;
  for (Vec3 c : corners) {
    const Vec3 q = view.project(c);
    // A corner at or behind the eye plane projects nowhere useful: keep the whole image.
    if (view.projection == Projection::perspective && !(q.z > 1e-4f)) return all;
    x0 = std::min(x0, q.x);
    y0 = std::min(y0, q.y);
    x1 = std::max(x1, q.x);
    y1 = std::max(y1, q.y);
  }
  // Pixel x is inside when its centre x + 0.5 lies in [x0, x1]; one pixel of slack for rounding.
  auto lo = [](float v, int n) { return int(std::clamp(std::floor(v - 0.5f) - 1.0f, 0.0f, float(n))); };
  auto hi = [](float v, int n) { return int(std::clamp(std::ceil(v - 0.5f) + 2.0f, 0.0f, float(n))); };
  return {lo(x0, view.resolution.x), lo(y0, view.resolution.y), hi(x1, view.resolution.x),
          hi(y1, view.resolution.y)};
}

}  // namespace caligo
