#include "realtime/surface_shading.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "core/overloaded.h"
#include "core/parallel.h"
#include "realtime/surface_shading_internal.h"
#include "lights/light_profile.h"
#include "realtime/media.h"
#include "realtime/shadow_map.h"
#include "scene/scene.h"

namespace caligo {
namespace {

// Wide, short tiles: each tile row streams whole cache lines of the seven G-buffer and output
// planes (16 x 16 tiles touched one line per plane per row, 7.7 KB apart, and the SIMD loop
// stalled on those loads; 64 x 4 cut its no-light cost by about a third).
constexpr int kTileWidth = 64, kTileHeight = 4;

// Light arriving at a surface point from one light, before shadowing and media.
struct Incident {
  RGB radiance;      // irradiance on a surface facing the light (delta lights)
  Vec3 wi;           // unit, towards the light
  Vec3 light_point;  // where the light's path starts (for the media between)
};

// The light at p from `light` (lights/light_profile.h, the path tracer's light exactly); the
// light point of a parallel light is `far` away, beyond every surface and volume.
std::optional<Incident> incident_at(const ShadedLight& light, Vec3 p, float far) {
  const auto a = std::visit([&](const auto& l) { return delta_arrival(l, p); }, light);
  if (!a) return std::nullopt;
  return Incident{a->radiance, a->wi, p + a->wi * std::min(a->distance, far)};
}

bool sphere_overlaps(Vec3 c, float r, const Bounds3& b) {
  if (!std::isfinite(r)) return true;
  const Vec3 q = min(max(c, b.lo), b.hi);
  return length_squared(q - c) <= r * r;
}

bool overlaps(const Bounds3& a, const Bounds3& b) {
  return a.lo.x <= b.hi.x && a.hi.x >= b.lo.x && a.lo.y <= b.hi.y && a.hi.y >= b.lo.y && a.lo.z <= b.hi.z &&
         a.hi.z >= b.lo.z;
}

Bounds3 box_light_bounds(const BoxLight& l) {
  const Vec3 right = cross(l.direction, l.up);
  Bounds3 b;
  for (int i = 0; i < 8; ++i)
    b.extend(l.position + right * ((i & 1) ? l.half_width : -l.half_width) +
             l.up * ((i & 2) ? l.half_height : -l.half_height) + l.direction * ((i & 4) ? l.range : 0.0f));
  return b;
}

// Conservative: may the light reach any point of `tile`?
struct Reaches {
  const Bounds3& tile;
  bool operator()(const PointLight& l) const { return sphere_overlaps(l.position, l.range, tile); }
  bool operator()(const SpotLight& l) const {
    return sphere_overlaps(l.position, l.range, tile) && shading::spot_cone_may_reach(l, tile);
  }
  bool operator()(const BoxLight& l) const { return overlaps(box_light_bounds(l), tile); }
  bool operator()(const DirectionalLight&) const { return true; }
};

}  // namespace

namespace shading {

// The box's bounding sphere against the cone (Wronski, "Cull that cone!", 2017).
bool spot_cone_may_reach(const SpotLight& l, const Bounds3& b) {
  if (!(l.cos_outer > 0.0f)) return true;
  const Vec3 v = b.center() - l.position;
  const float radius = 0.5f * length(b.diagonal());
  const float along = dot(v, l.direction);
  const float across = std::sqrt(std::max(length_squared(v) - along * along, 0.0f));
  const float sin_outer = std::sqrt(std::max(1.0f - l.cos_outer * l.cos_outer, 0.0f));
  // Distance from the sphere's centre to the cone's surface (negative inside); a relative
  // margin keeps rounding from culling a sphere that grazes the cone.
  const float outside = l.cos_outer * across - along * sin_outer;
  return outside <= radius * 1.001f + 1e-4f && along >= -radius;
}

// Far enough along any direction to leave every surface and volume from inside them.
float escape_distance(const Scene& scene) {
  Bounds3 b = scene.surfaces().bounds();
  for (const VolumePrimitive& v : scene.volumes().primitives()) b.extend(volume_bounds(v.shape));
  return b.empty() ? 1.0f : 2.0f * length(b.diagonal()) + 1.0f;
}

RGB transmittance(const VolumeScene& volumes, Vec3 a, Vec3 b) {
  if (volumes.empty()) return RGB(1.0f);
  const RGB tau = segment_optical_depth(volumes, a, b);
  return exp_neg(tau);
}

RGB light_term(const ShadeContext& c, const FrameLight& fl, Vec3 p, Vec3 n, RGB f) {
  const auto in = incident_at(fl.light, p, c.far);
  if (!in) return RGB(0.0f);
  const float cos_theta = dot(n, in->wi);
  if (!(cos_theta > 0.0f)) return RGB(0.0f);
  // Normal offset: one texel towards the lit side keeps self-shadowing acne away.
  const ShadowMap* map = fl.surface_map();
  const float visible = map ? map->surface_visibility(p + n * map->texel_size(p)) : 1.0f;
  if (visible == 0.0f) return RGB(0.0f);
  return f * in->radiance * (cos_theta * visible) * transmittance(c.scene.volumes(), p, in->light_point);
}

std::optional<RGB> diffuse_f(const Bsdf& bsdf) {
  return std::visit(Overloaded{[](const DiffuseBsdf& d) -> std::optional<RGB> { return d.reflectance * kInvPi; },
                               [](const DielectricBsdf&) -> std::optional<RGB> { return std::nullopt; },
                               [](const BlackBsdf&) -> std::optional<RGB> { return std::nullopt; },
                               [](const NullBsdf&) -> std::optional<RGB> { return std::nullopt; }},
                    bsdf);
}

RGB shade_pixel(const ShadeContext& c, size_t pixel, Vec3 p, Vec3 eye, std::span<const int> active) {
  const Material& m = c.scene.materials()[size_t(c.g.material[pixel])];
  RGB radiance;
  if (!m.emission.is_black() && (c.g.front[pixel] || m.two_sided_emission)) radiance += m.emission;
  if (const std::optional<RGB> f = diffuse_f(m.bsdf)) {
    const Vec3 n{c.g.nx.data[pixel], c.g.ny.data[pixel], c.g.nz.data[pixel]};
    for (int i : active) radiance += light_term(c, c.lights[size_t(i)], p, n, *f);
  }
  return radiance * transmittance(c.scene.volumes(), eye, p);
}

}  // namespace shading

namespace {

using shading::ShadeContext;

// The surface point of pixel (x, y) at linear depth `depth`, and the camera ray's origin.
// The unnormalised perspective direction has unit forward component, so p = eye + d * depth
// (the same arithmetic as the SIMD path's load_group).
Vec3 pixel_point(const View& v, int x, int y, float depth, Vec3& eye) {
  const float ndc_x = 2.0f * (float(x) + 0.5f) / float(v.resolution.x) - 1.0f;
  const float ndc_y = 1.0f - 2.0f * (float(y) + 0.5f) / float(v.resolution.y);
  if (v.projection == Projection::perspective) {
    eye = v.eye;
    const Vec3 d =
        v.forward + v.right * (ndc_x * v.tan_half_fov_y * v.aspect) + v.up * (ndc_y * v.tan_half_fov_y);
    return eye + d * depth;
  }
  eye = v.eye + v.right * (ndc_x * v.half_width) + v.up * (ndc_y * v.half_height);
  return eye + v.forward * depth;
}

void shade_tile(const ShadeContext& c, const shading::SimdFrame* simd, const Tile& tile, ColorPlanes& out) {
  const int w = c.g.depth.width;
  // The SIMD path takes the columns that fill whole batches; the scalar one the rest.
  const int x_simd = simd ? tile.x0 + (tile.x1 - tile.x0) / 8 * 8 : tile.x0;
  const int cols = tile.x1 - x_simd;
  Vec3 points[kTileWidth * kTileHeight], eyes[kTileWidth * kTileHeight];
  Bounds3 bounds = simd ? shading::points_bounds_simd(c, tile.y0, tile.y1, tile.x0, x_simd) : Bounds3{};
  for (int y = tile.y0; y < tile.y1; ++y)
    for (int x = x_simd; x < tile.x1; ++x) {
      const float depth = c.g.depth.at(x, y);
      if (depth >= kSkyDepth) continue;
      const size_t k = size_t(y - tile.y0) * size_t(cols) + size_t(x - x_simd);
      points[k] = pixel_point(c.camera, x, y, depth, eyes[k]);
      bounds.extend(points[k]);
    }
  if (bounds.empty()) {  // all sky
    for (int y = tile.y0; y < tile.y1; ++y)
      for (int x = tile.x0; x < tile.x1; ++x) out.set(x, y, RGB(0.0f));
    return;
  }
  std::vector<int> active;
  for (size_t i = 0; i < c.lights.size(); ++i)
    if (std::visit(Reaches{bounds}, c.lights[i].light)) active.push_back(int(i));
  if (simd) shading::shade_rect_simd(c, *simd, tile.y0, tile.y1, tile.x0, x_simd, active, bounds, out);
  for (int y = tile.y0; y < tile.y1; ++y) {
    for (int x = x_simd; x < tile.x1; ++x) {
      if (c.g.depth.at(x, y) >= kSkyDepth) {
        out.set(x, y, RGB(0.0f));
        continue;
      }
      const size_t k = size_t(y - tile.y0) * size_t(cols) + size_t(x - x_simd);
      out.set(x, y, shading::shade_pixel(c, size_t(y) * size_t(w) + size_t(x), points[k], eyes[k], active));
    }
  }
}

std::vector<Tile> shading_tiles(int w, int h) {
  std::vector<Tile> tiles;
  for (int y = 0; y < h; y += kTileHeight)
    for (int x = 0; x < w; x += kTileWidth)
      tiles.push_back({x, y, std::min(x + kTileWidth, w), std::min(y + kTileHeight, h), int(tiles.size())});
  return tiles;
}

}  // namespace

ColorPlanes shade_surfaces(const GBuffer& gbuffer, const View& camera, const Scene& scene,
                           std::span<const FrameLight> lights, bool simd) {
  ColorPlanes out;
  shade_surfaces(gbuffer, camera, scene, lights, out, simd);
  return out;
}

void shade_surfaces(const GBuffer& gbuffer, const View& camera, const Scene& scene,
                    std::span<const FrameLight> lights, ColorPlanes& out, bool simd) {
  const int w = gbuffer.depth.width, h = gbuffer.depth.height;
  // Every pixel is written below: a buffer of the right size is reused as it is.
  if (out.width() != w || out.height() != h) out = ColorPlanes(w, h);
  const ShadeContext context{gbuffer, camera, scene, lights, shading::escape_distance(scene), simd};
  const shading::SimdFramePtr frame = simd ? shading::prepare_simd(context) : nullptr;
  parallel_for_tiles(shading_tiles(w, h),
                     [&](const Tile& tile) { shade_tile(context, frame.get(), tile, out); });
}

}  // namespace caligo
