#include "realtime/shadow_map.h"

#include <cmath>

#include "realtime/directional_faces.h"
#include "realtime/scene_buffers.h"

namespace caligo {
namespace {

// Spot cones wider than this get a cube: one perspective face would need a field of view
// near 180 degrees and spend its texels at the rim.
constexpr float kMaxSpotHalfAngle = 75.0f * kPi / 180.0f;

ShadowMap cube_map(const RasterScene& scene, Vec3 position, int size, int32_t skip) {
  const Vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  ShadowMap map;
  for (int f = 0; f < 6; ++f) {
    const Vec3 up_hint = (f == 2 || f == 3) ? Vec3{0, 0, 1} : Vec3{0, 1, 0};
    map.faces.push_back(View::perspective_view(position, axes[f], up_hint, 0.5f * kPi, {size, size}));
    map.depth.push_back(rasterize_depth(scene, map.faces.back(), true, skip));
  }
  return map;
}

ShadowMap single_face(const RasterScene& scene, const View& face, int32_t skip) {
  ShadowMap map;
  map.faces.push_back(face);
  map.depth.push_back(rasterize_depth(scene, face, true, skip));
  return map;
}

struct Render {
  const RasterScene& scene;
  int size;
  const Bounds3& bounds;
  int32_t skip;

  std::optional<ShadowMap> operator()(const PointLight& l) const { return cube_map(scene, l.position, size, skip); }
  std::optional<ShadowMap> operator()(const SpotLight& l) const {
    const float half_angle = std::acos(std::clamp(l.cos_outer, -1.0f, 1.0f));
    if (half_angle > kMaxSpotHalfAngle) return cube_map(scene, l.position, size, skip);
    return single_face(
        scene, View::perspective_view(l.position, l.direction, l.up, 2.0f * half_angle, {size, size}), skip);
  }
  std::optional<ShadowMap> operator()(const BoxLight& l) const {
    return single_face(scene, View::orthographic_view(l.position, l.direction, l.up, l.half_width,
                                                      l.half_height, {size, size}), skip);
  }
  std::optional<ShadowMap> operator()(const DirectionalLight& l) const {
    if (bounds.empty()) return std::nullopt;
    return single_face(scene, fit_directional_face(bounds, l.direction, size), skip);
  }
};

// The same arithmetic, in the same order, as shadow_visibility in shadow_map_simd.h.
struct FaceLookup {
  float x, y, z, texel;
};
FaceLookup project_face(const View& v, Vec3 p) {
  const float dx = p.x - v.eye.x, dy = p.y - v.eye.y, dz = p.z - v.eye.z;
  const float z = dx * v.forward.x + dy * v.forward.y + dz * v.forward.z;
  const float xr = dx * v.right.x + dy * v.right.y + dz * v.right.z;
  const float yu = dx * v.up.x + dy * v.up.y + dz * v.up.z;
  const float w = float(v.resolution.x), h = float(v.resolution.y);
  float ndc_x, ndc_y, texel;
  if (v.projection == Projection::perspective) {
    const float inv = 1.0f / (z * v.tan_half_fov_y);
    ndc_x = xr * inv / v.aspect;
    ndc_y = yu * inv;
    texel = z * (2.0f * v.tan_half_fov_y / h);
  } else {
    ndc_x = xr / v.half_width;
    ndc_y = yu / v.half_height;
    texel = 2.0f * v.half_height / h;
  }
  return {(ndc_x + 1.0f) * 0.5f * w, (1.0f - ndc_y) * 0.5f * h, z, texel};
}

}  // namespace

int ShadowMap::face_index(Vec3 p) const {
  if (cascades) return cascades->face(dot(p - cascades->eye, cascades->forward));
  if (!is_cube()) return 0;
  const Vec3 d = p - faces[0].eye;
  const float ax = std::abs(d.x), ay = std::abs(d.y), az = std::abs(d.z);
  if (ax >= ay && ax >= az) return d.x >= 0.0f ? 0 : 1;
  if (ay >= az) return d.y >= 0.0f ? 2 : 3;
  return d.z >= 0.0f ? 4 : 5;
}

float ShadowMap::texel_size(Vec3 p) const {
  const View& v = faces[size_t(face_index(p))];
  return std::abs(project_face(v, p).texel);
}

float ShadowMap::visibility(Vec3 p) const {
  const int f = face_index(p);
  const View& v = faces[size_t(f)];
  const Plane& d = depth[size_t(f)];
  const FaceLookup q = project_face(v, p);
  if (v.projection == Projection::perspective && !(q.z > 0.0f)) return 1.0f;
  int ix = int(std::floor(q.x)), iy = int(std::floor(q.y));
  if (is_cube()) {
    // The dominant-axis face always holds p; clamp rounding at its rim.
    ix = std::clamp(ix, 0, d.width - 1);
    iy = std::clamp(iy, 0, d.height - 1);
  } else if (!(q.x >= 0.0f && q.x < float(d.width) && q.y >= 0.0f && q.y < float(d.height))) {
    return 1.0f;
  }
  const float stored = d.data[size_t(iy) * size_t(d.width) + size_t(ix)];
  return q.z <= stored + (bias + texel_bias * q.texel) ? 1.0f : 0.0f;
}

// The same arithmetic, in the same order, as filtered_face_visibility in shadow_map_simd.h.
float ShadowMap::surface_visibility(Vec3 p) const {
  if (!filter_surfaces) return visibility(p);
  const int f = face_index(p);
  const View& v = faces[size_t(f)];
  const Plane& d = depth[size_t(f)];
  const FaceLookup q = project_face(v, p);
  if (v.projection == Projection::perspective && !(q.z > 0.0f)) return 1.0f;
  if (!is_cube() && !(q.x >= 0.0f && q.x < float(d.width) && q.y >= 0.0f && q.y < float(d.height))) return 1.0f;
  const float slack = bias + texel_bias * q.texel;
  const float gx = q.x - 0.5f, gy = q.y - 0.5f;
  const float x0 = std::floor(gx), y0 = std::floor(gy);
  const float tx = gx - x0, ty = gy - y0;
  const auto tap = [&](int x, int y) {
    if (is_cube()) {
      x = std::clamp(x, 0, d.width - 1);
      y = std::clamp(y, 0, d.height - 1);
    } else if (x < 0 || x >= d.width || y < 0 || y >= d.height) {
      return 1.0f;
    }
    return q.z <= d.data[size_t(y) * size_t(d.width) + size_t(x)] + slack ? 1.0f : 0.0f;
  };
  const int ix = int(x0), iy = int(y0);
  const float top = tap(ix, iy) + tx * (tap(ix + 1, iy) - tap(ix, iy));
  const float bottom = tap(ix, iy + 1) + tx * (tap(ix + 1, iy + 1) - tap(ix, iy + 1));
  return top + ty * (bottom - top);
}

namespace {

bool same_face(const View& a, const View& b) {
  return a.eye == b.eye && a.forward == b.forward && a.up == b.up && a.half_width == b.half_width &&
         a.half_height == b.half_height && a.resolution.x == b.resolution.x && a.resolution.y == b.resolution.y;
}

}  // namespace

int update_cascaded_shadow_map(const RasterScene& scene, const CascadeFaces& fit, const View& camera,
                               int32_t skip_emitter, ShadowMap& map, const ShadowMap* whole) {
  int rendered = 0;
  bool deferred_one = false;  // at most one face that still covers its slice is redrawn a frame
  const bool fresh = map.faces.size() != fit.faces.size();
  map.faces.resize(fit.faces.size());
  map.depth.resize(fit.faces.size());
  for (size_t i = 0; i < fit.faces.size(); ++i) {
    const bool drawn = !fresh && map.depth[i].width > 0;
    if (drawn && same_face(map.faces[i], fit.faces[i])) continue;
    if (drawn && covers(map.faces[i], fit.needed[i])) {
      if (deferred_one) continue;
      deferred_one = true;
    }
    map.faces[i] = fit.faces[i];
    if (whole && whole->single_face() && same_face(whole->faces[0], fit.faces[i])) {
      map.depth[i] = whole->depth[0];
      continue;
    }
    map.depth[i] = rasterize_depth(scene, fit.faces[i], true, skip_emitter);
    ++rendered;
  }
  map.cascades = ShadowMap::Cascades{camera.eye, camera.forward, fit.far};
  return rendered;
}

std::optional<ShadowMap> render_shadow_map(const RasterScene& scene, const ShadedLight& light, int size,
                                           const Bounds3& scene_bounds, int32_t skip_emitter) {
  return std::visit(Render{scene, size, scene_bounds, skip_emitter}, light);
}

}  // namespace caligo
