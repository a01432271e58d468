// Shadow-volume geometry and the eye's winding number (shadow_volume.h): the volume built
// from the occluder's silhouette and caps, and containment by signed segment crossings.
#include "hybrid/shadow_volume.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/ray_solids.h"

namespace caligo {
namespace {

Vec3 extrude(Vec3 p, Vec3 light, float extrusion) {
  const Vec3 d = p - light;
  const float len = length(d);
  // A vertex at the light cannot be extruded; no lit triangle has one, as it would face
  // the light edge-on.
  return len > 0.0f ? p + d * (extrusion / len) : p;
}

// Segment p -> q against triangle (a, b, c) in double (Moller-Trumbore). Returns 0 for no
// crossing, +1 when the segment leaves through the face's front (outward) side, -1 when it
// enters; sets *grazing when the crossing is too close to an edge or an end to trust.
int segment_crossing(const double p[3], const double q[3], Vec3 a, Vec3 b, Vec3 c, bool* grazing) {
  const double d[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
  const double e1[3] = {double(b.x) - a.x, double(b.y) - a.y, double(b.z) - a.z};
  const double e2[3] = {double(c.x) - a.x, double(c.y) - a.y, double(c.z) - a.z};
  const double h[3] = {d[1] * e2[2] - d[2] * e2[1], d[2] * e2[0] - d[0] * e2[2], d[0] * e2[1] - d[1] * e2[0]};
  const double det = e1[0] * h[0] + e1[1] * h[1] + e1[2] * h[2];
  if (det == 0.0) return 0;  // segment parallel to the plane: crosses nothing
  const double inv = 1.0 / det;
  const double s[3] = {p[0] - a.x, p[1] - a.y, p[2] - a.z};
  const double u = (s[0] * h[0] + s[1] * h[1] + s[2] * h[2]) * inv;
  const double qv[3] = {s[1] * e1[2] - s[2] * e1[1], s[2] * e1[0] - s[0] * e1[2],
                        s[0] * e1[1] - s[1] * e1[0]};
  const double v = (d[0] * qv[0] + d[1] * qv[1] + d[2] * qv[2]) * inv;
  const double t = (e2[0] * qv[0] + e2[1] * qv[1] + e2[2] * qv[2]) * inv;
  constexpr double kEps = 1e-7;
  const double w = 1.0 - u - v;
  if (u < -kEps || v < -kEps || w < -kEps || t < -kEps || t > 1.0 + kEps) return 0;
  if (u < kEps || v < kEps || w < kEps || t < kEps || t > 1.0 - kEps) {
    *grazing = true;
    return 0;
  }
  // det = e1 . (d x e2) = d . (e2 x e1) = -d . n: det < 0 means the segment runs along the
  // outward normal, i.e. it leaves the volume.
  return det < 0.0 ? 1 : -1;
}

bool segment_hits_box(Vec3 p, Vec3 q, const Bounds3& b) {
  if (b.empty()) return false;
  // Pad the box: the slab test in float must not reject a segment the exact test accepts.
  Bounds3 padded = b;
  const float pad =
      1e-4f * (1.0f + max_component(max(Vec3(std::abs(b.lo.x), std::abs(b.lo.y), std::abs(b.lo.z)),
                                        Vec3(std::abs(b.hi.x), std::abs(b.hi.y), std::abs(b.hi.z)))));
  padded.lo = padded.lo - Vec3(pad);
  padded.hi = padded.hi + Vec3(pad);
  return ray_box(p, q - p, padded.lo, padded.hi, 0.0f, 1.0f).has_value();
}

// Winding number towards one target; false when some crossing grazed an edge.
bool winding_towards(const ShadowVolume& v, Vec3 point, Vec3 target, int* winding) {
  const double p[3] = {point.x, point.y, point.z}, q[3] = {target.x, target.y, target.z};
  const auto& pos = v.mesh.positions;
  const auto& idx = v.mesh.indices;
  bool grazing = false;
  int sum = 0;
  auto range = [&](size_t begin, size_t count) {
    for (size_t t = begin; t < begin + count && !grazing; ++t)
      sum += segment_crossing(p, q, pos[idx[3 * t]], pos[idx[3 * t + 1]], pos[idx[3 * t + 2]], &grazing);
  };
  range(v.side_begin(), v.side_triangles);
  // The near cap lies on the occluder and the far cap beyond min_far_distance from the
  // light: most eye positions skip both tests.
  if (segment_hits_box(point, target, v.occluder_bounds)) range(v.near_cap_begin(), v.near_cap_triangles);
  if (distance(point, v.light) >= 0.999f * v.min_far_distance) range(v.far_cap_begin(), v.far_cap_triangles);
  *winding = sum;
  return !grazing;
}

}  // namespace

ShadowVolume build_shadow_volume(const MeshEdges& occluder, Vec3 light, float extrusion) {
  if (!occluder.closed())
    throw std::invalid_argument("shadow volume of a mesh that is not closed: " + occluder.problem());
  if (!(extrusion > 0.0f) || !std::isfinite(extrusion))
    throw std::invalid_argument("shadow volume extrusion must be positive and finite");
  ShadowVolume v;
  v.light = light;
  v.extrusion = extrusion;
  const Silhouette sil = find_silhouette(occluder, light);
  const auto& verts = occluder.vertices();
  const uint32_t n = uint32_t(verts.size());
  v.mesh.positions = verts;
  v.mesh.positions.reserve(2 * size_t(n));
  v.min_far_distance = kInfinity;
  for (Vec3 p : verts) v.mesh.positions.push_back(extrude(p, light, extrusion));

  auto& idx = v.mesh.indices;
  idx.reserve(3 * (2 * sil.edges.size() + 2 * sil.lit_count));
  for (const auto& [a, b] : sil.edges) {  // the lit triangle traverses a -> b
    idx.insert(idx.end(), {b, a, a + n});
    idx.insert(idx.end(), {b, a + n, b + n});
  }
  v.side_triangles = 2 * sil.edges.size();
  const auto& tris = occluder.triangles();
  for (size_t t = 0; t < tris.size(); ++t) {
    if (!sil.lit[t]) continue;
    idx.insert(idx.end(), {tris[t][0], tris[t][1], tris[t][2]});
    for (uint32_t k : tris[t]) {
      v.occluder_bounds.extend(verts[k]);
      v.min_far_distance = std::min(v.min_far_distance, distance(v.mesh.positions[k + n], light));
    }
  }
  v.near_cap_triangles = sil.lit_count;
  // Central projection from the light keeps a triangle's winding as seen from the light,
  // so the far copy must be reversed to face away from it (outwards).
  for (size_t t = 0; t < tris.size(); ++t)
    if (sil.lit[t]) idx.insert(idx.end(), {tris[t][0] + n, tris[t][2] + n, tris[t][1] + n});
  v.far_cap_triangles = sil.lit_count;
  return v;
}

float extrusion_for(const Bounds3& scene_bounds, Vec3 light) {
  Bounds3 b = scene_bounds;
  b.extend(light);
  return 1.01f * length(b.diagonal()) + 1.0f;
}

int volumes_containing(const ShadowVolume& volume, Vec3 point) {
  // The light is outside the volume (the volume starts at the occluder's lit surface), so
  // the signed crossings of point -> light give the winding number. A segment through an
  // edge or vertex would count a crossing twice or not at all; such targets are rejected
  // and the light jittered by a tiny, deterministic amount instead.
  const float scale = 1e-4f * std::max(1.0f, length(point - volume.light));
  static constexpr float kJitter[8][3] = {
      {0.31f, 0.77f, -0.52f}, {-0.68f, 0.12f, 0.71f},  {0.45f, -0.83f, 0.29f},  {-0.19f, -0.41f, -0.89f},
      {0.93f, 0.27f, 0.22f},  {-0.57f, 0.61f, -0.55f}, {0.08f, -0.97f, -0.21f}, {0.66f, 0.49f, 0.57f}};
  int winding = 0;
  if (winding_towards(volume, point, volume.light, &winding)) return winding;
  for (const auto& j : kJitter)
    if (winding_towards(volume, point, volume.light + Vec3(j[0], j[1], j[2]) * scale, &winding))
      return winding;
  return winding;  // every target grazed: astronomically unlikely; keep the last count
}

}  // namespace caligo
