// Triangle set-up: world -> view space, clipping against the near plane and a guard band
// (in view space, so attributes stay linear), projection, edge functions and tile binning.
#include "realtime/raster_setup.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"

namespace caligo::raster {
namespace {

// Perspective near plane (metres). Triangles crossing it are clipped, not dropped.
constexpr float kNear = 1.0e-4f;
// Guard band: clip to |ndc| <= 3 so screen coordinates stay within one viewport of the
// screen and the float edge functions keep sub-pixel accuracy.
constexpr float kGuard = 3.0f;
constexpr int kMaxPolygon = 9;  // a triangle clipped by 5 planes has at most 8 vertices
constexpr size_t kChunk = 2048;

struct ViewVertex {
  float x, y, z;
  Vec3 n;
};

struct ScreenVertex {
  float x, y, key;
  Vec3 n;
};

struct Projector {
  const View& view;
  bool perspective;
  float half_w, half_h;    // viewport half size, pixels
  float scale_x, scale_y;  // view-space x/z (or x) -> pixels
  float guard_x, guard_y;  // |x| <= guard_x * z (perspective) or guard_x (orthographic)

  explicit Projector(const View& v)
      : view(v),
        perspective(v.projection == Projection::perspective),
        half_w(0.5f * float(v.resolution.x)),
        half_h(0.5f * float(v.resolution.y)) {
    const float kx = perspective ? v.tan_half_fov_y * v.aspect : v.half_width;
    const float ky = perspective ? v.tan_half_fov_y : v.half_height;
    scale_x = half_w / kx;
    scale_y = half_h / ky;
    guard_x = kGuard * kx;
    guard_y = kGuard * ky;
  }

  ViewVertex to_view(Vec3 p, Vec3 n) const {
    const Vec3 d = p - view.eye;
    return {dot(d, view.right), dot(d, view.up), dot(d, view.forward), n};
  }
  // Signed distance-like value to clip plane k; >= 0 inside.
  float plane(int k, const ViewVertex& v) const {
    const float w = perspective ? v.z : 1.0f;
    switch (k) {
      case 0:
        return perspective ? v.z - kNear : v.z;
      case 1:
        return guard_x * w - v.x;
      case 2:
        return guard_x * w + v.x;
      case 3:
        return guard_y * w - v.y;
      default:
        return guard_y * w + v.y;
    }
  }
  bool inside(const ViewVertex& v) const {
    for (int k = 0; k < 5; ++k)
      if (!(plane(k, v) >= 0.0f)) return false;
    return true;
  }
  ScreenVertex project(const ViewVertex& v) const {
    if (perspective) {
      const float iz = 1.0f / v.z;
      return {half_w + v.x * scale_x * iz, half_h - v.y * scale_y * iz, iz, v.n};
    }
    return {half_w + v.x * scale_x, half_h - v.y * scale_y, -v.z, v.n};
  }
};

// Sutherland-Hodgman. Each crossing point is interpolated from the inside vertex towards
// the outside one, so the two triangles sharing an edge create bit-identical vertices.
int clip_polygon(const Projector& proj, ViewVertex* poly, int n) {
  ViewVertex tmp[kMaxPolygon];
  for (int k = 0; k < 5 && n > 0; ++k) {
    int m = 0;
    for (int i = 0; i < n; ++i) {
      const ViewVertex& a = poly[i];
      const ViewVertex& b = poly[(i + 1) % n];
      const float da = proj.plane(k, a), db = proj.plane(k, b);
      const bool a_in = da >= 0.0f, b_in = db >= 0.0f;
      if (a_in) tmp[m++] = a;
      if (a_in != b_in) {
        const ViewVertex& in = a_in ? a : b;
        const ViewVertex& out = a_in ? b : a;
        const float d_in = a_in ? da : db, d_out = a_in ? db : da;
        const float t = d_in / (d_in - d_out);
        tmp[m++] = {in.x + (out.x - in.x) * t, in.y + (out.y - in.y) * t, in.z + (out.z - in.z) * t,
                    in.n + (out.n - in.n) * t};
      }
    }
    std::copy(tmp, tmp + m, poly);
    n = m;
  }
  return n;
}

bool lexicographically_less(const ScreenVertex& a, const ScreenVertex& b) {
  return a.x < b.x || (a.x == b.x && a.y < b.y);
}

// e(p) for the edge a -> b, evaluated from the canonical end (see raster_setup.h).
void set_edge(ScreenTri& t, int i, const ScreenVertex& a, const ScreenVertex& b) {
  if (lexicographically_less(a, b)) {
    t.ax[i] = a.x, t.ay[i] = a.y, t.dx[i] = b.x - a.x, t.dy[i] = b.y - a.y, t.tie[i] = true;
  } else {
    t.ax[i] = b.x, t.ay[i] = b.y, t.dx[i] = -(a.x - b.x), t.dy[i] = -(a.y - b.y), t.tie[i] = false;
  }
}

float edge(const ScreenVertex& a, const ScreenVertex& b, const ScreenVertex& p) {
  return (p.x - a.x) * (b.y - a.y) - (p.y - a.y) * (b.x - a.x);
}

// Perspective-correct planes of the shading normal: n * w is affine in screen space.
void set_normal_planes(ScreenTri& t, const ScreenVertex* v, float area, bool perspective) {
  t.ref_x = v[2].x, t.ref_y = v[2].y;
  const float w0 = perspective ? v[0].key : 1.0f, w1 = perspective ? v[1].key : 1.0f,
              w2 = perspective ? v[2].key : 1.0f;
  const float inv_area = 1.0f / area;
  for (int k = 0; k < 3; ++k) {
    const float a2 = v[2].n[k] * w2, d0 = v[0].n[k] * w0 - a2, d1 = v[1].n[k] * w1 - a2;
    t.n_base[k] = a2;
    t.n_gx[k] = ((v[2].y - v[1].y) * d0 + (v[0].y - v[2].y) * d1) * inv_area;
    t.n_gy[k] = (-(v[2].x - v[1].x) * d0 - (v[0].x - v[2].x) * d1) * inv_area;
  }
}

void emit_triangle(ScreenVertex v0, ScreenVertex v1, ScreenVertex v2, uint32_t source, const Projector& proj,
                   bool attributes, std::vector<ScreenTri>& out) {
  float area = edge(v0, v1, v2);
  if (area < 0.0f) {
    std::swap(v1, v2);
    area = edge(v0, v1, v2);
  }
  if (!(area > 0.0f) || !std::isfinite(area)) return;  // edge-on or degenerate after projection
  ScreenTri t;
  const float min_x = std::min({v0.x, v1.x, v2.x}), max_x = std::max({v0.x, v1.x, v2.x});
  const float min_y = std::min({v0.y, v1.y, v2.y}), max_y = std::max({v0.y, v1.y, v2.y});
  const int w = proj.view.resolution.x, h = proj.view.resolution.y;
  // Pixel x is a candidate when its centre x + 0.5 lies within [min_x, max_x].
  t.x0 = std::max(0, int(std::ceil(min_x - 0.5f)));
  t.x1 = std::min(w, int(std::floor(max_x - 0.5f)) + 1);
  t.y0 = std::max(0, int(std::ceil(min_y - 0.5f)));
  t.y1 = std::min(h, int(std::floor(max_y - 0.5f)) + 1);
  if (t.x0 >= t.x1 || t.y0 >= t.y1) return;
  set_edge(t, 0, v1, v2);
  set_edge(t, 1, v2, v0);
  set_edge(t, 2, v0, v1);
  t.c[0] = v0.key / area, t.c[1] = v1.key / area, t.c[2] = v2.key / area;
  t.source = source;
  const ScreenVertex v[3] = {v0, v1, v2};
  if (attributes) set_normal_planes(t, v, area, proj.perspective);
  out.push_back(t);
}

void setup_one(const RasterScene& scene, size_t i, const Projector& proj, bool attributes,
               std::vector<ScreenTri>& out) {
  const Vec3* p = scene.vertices(i);
  const Vec3* n = scene.vertex_normals(i);
  ViewVertex poly[kMaxPolygon] = {proj.to_view(p[0], n[0]), proj.to_view(p[1], n[1]),
                                  proj.to_view(p[2], n[2])};
  int count = 3;
  if (!(proj.inside(poly[0]) && proj.inside(poly[1]) && proj.inside(poly[2]))) {
    // Trivially outside one plane: nothing to draw.
    for (int k = 0; k < 5; ++k)
      if (proj.plane(k, poly[0]) < 0.0f && proj.plane(k, poly[1]) < 0.0f && proj.plane(k, poly[2]) < 0.0f)
        return;
    count = clip_polygon(proj, poly, 3);
  }
  if (count < 3) return;
  const ScreenVertex first = proj.project(poly[0]);
  ScreenVertex prev = proj.project(poly[1]);
  for (int k = 2; k < count; ++k) {
    const ScreenVertex cur = proj.project(poly[k]);
    emit_triangle(first, prev, cur, uint32_t(i), proj, attributes, out);
    prev = cur;
  }
}

}  // namespace

Setup setup_triangles(const RasterScene& scene, const View& view, bool attributes, int32_t skip_emitter) {
  Setup s;
  s.width = view.resolution.x;
  s.height = view.resolution.y;
  s.perspective = view.projection == Projection::perspective;
  s.tiles_x = (s.width + kTileSize - 1) / kTileSize;
  s.tiles_y = (s.height + kTileSize - 1) / kTileSize;
  const Projector proj(view);

  const size_t n = scene.triangle_count();
  const int chunks = int((n + kChunk - 1) / kChunk);
  std::vector<std::vector<ScreenTri>> parts(static_cast<size_t>(chunks));
  parallel_for(chunks, [&](int c) {
    const size_t begin = size_t(c) * kChunk, end = std::min(n, begin + kChunk);
    parts[size_t(c)].reserve(end - begin);
    for (size_t i = begin; i < end; ++i)
      if (skip_emitter < 0 || scene.emitter(i) != skip_emitter) setup_one(scene, i, proj, attributes, parts[size_t(c)]);
  });

  size_t total = 0;
  for (const auto& part : parts) total += part.size();
  s.tris.reserve(total);
  for (const auto& part : parts) s.tris.insert(s.tris.end(), part.begin(), part.end());

  // Binning stays serial and in scene order so ties in depth resolve the same every run.
  s.bins.resize(size_t(s.tiles_x) * size_t(s.tiles_y));
  for (uint32_t i = 0; i < uint32_t(s.tris.size()); ++i) {
    const ScreenTri& t = s.tris[i];
    for (int ty = t.y0 / kTileSize; ty <= (t.y1 - 1) / kTileSize; ++ty)
      for (int tx = t.x0 / kTileSize; tx <= (t.x1 - 1) / kTileSize; ++tx)
        s.bins[size_t(ty) * size_t(s.tiles_x) + size_t(tx)].push_back(i);
  }
  return s;
}

}  // namespace caligo::raster
