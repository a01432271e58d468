// Test-only helpers for mesh_edges_test.cpp and shadow_volume_test.cpp: closed occluder
// meshes built without shared vertex indices (so welding is exercised), and a double-
// precision ray-triangle test for brute-force references.
#pragma once

#include <array>
#include <cmath>
#include <optional>
#include <vector>

#include "core/math.h"
#include "geometry/triangle_mesh.h"

namespace caligo::testing {

inline void add_triangle(TriangleMesh& m, Vec3 a, Vec3 b, Vec3 c) {
  for (Vec3 p : {a, b, c}) {
    m.indices.push_back(uint32_t(m.positions.size()));
    m.positions.push_back(p);
  }
}

// Axis-aligned box, outward winding, 4 separate vertices per face (24 in all).
inline TriangleMesh box_mesh(Vec3 lo, Vec3 hi) {
  TriangleMesh m;
  auto corner = [&](int i) { return Vec3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z); };
  // Each face as 4 corner ids, counter-clockwise seen from outside.
  const int faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& f : faces) {
    add_triangle(m, corner(f[0]), corner(f[1]), corner(f[2]));
    add_triangle(m, corner(f[0]), corner(f[2]), corner(f[3]));
  }
  return m;
}

// Icosahedron subdivided `levels` times onto the sphere, unindexed (3 vertices per
// triangle): 20 * 4^levels triangles.
inline TriangleMesh sphere_mesh(Vec3 centre, float radius, int levels) {
  const float g = (1.0f + std::sqrt(5.0f)) * 0.5f;
  std::vector<Vec3> v = {{-1, g, 0},  {1, g, 0},  {-1, -g, 0}, {1, -g, 0}, {0, -1, g},  {0, 1, g},
                         {0, -1, -g}, {0, 1, -g}, {g, 0, -1},  {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
  for (Vec3& p : v) p = normalize(p);
  std::vector<std::array<Vec3, 3>> tris;
  const int f[20][3] = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                        {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                        {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (const auto& t : f) tris.push_back({v[size_t(t[0])], v[size_t(t[1])], v[size_t(t[2])]});
  for (int l = 0; l < levels; ++l) {
    std::vector<std::array<Vec3, 3>> next;
    // a + b is commutative in IEEE arithmetic, so both triangles of an edge get the same midpoint.
    auto mid = [](Vec3 a, Vec3 b) { return normalize(a + b); };
    for (const auto& t : tris) {
      const Vec3 ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
      next.push_back({t[0], ab, ca});
      next.push_back({t[1], bc, ab});
      next.push_back({t[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    tris.swap(next);
  }
  TriangleMesh m;
  for (const auto& t : tris)
    add_triangle(m, centre + t[0] * radius, centre + t[1] * radius, centre + t[2] * radius);
  return m;
}

// Torus around the y axis: major radius R, minor r, n x m quads, unindexed.
inline TriangleMesh torus_mesh(Vec3 centre, float R, float r, int n, int m) {
  auto point = [&](int i, int j) {
    const float u = 2.0f * kPi * float(i % n) / float(n), v = 2.0f * kPi * float(j % m) / float(m);
    const float rho = R + r * std::cos(v);
    return centre + Vec3(rho * std::cos(u), r * std::sin(v), rho * std::sin(u));
  };
  TriangleMesh mesh;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const Vec3 a = point(i, j), b = point(i + 1, j), c = point(i + 1, j + 1), d = point(i, j + 1);
      add_triangle(mesh, a, c, b);
      add_triangle(mesh, a, d, c);
    }
  return mesh;
}

inline void append(TriangleMesh& to, const TriangleMesh& from) {
  const uint32_t base = uint32_t(to.positions.size());
  to.positions.insert(to.positions.end(), from.positions.begin(), from.positions.end());
  for (uint32_t i : from.indices) to.indices.push_back(base + i);
}

struct DVec {
  double x, y, z;
};

// Ray o + t d against triangle (a, b, c) in double: t > 0 on a hit, and the sign of
// dot(d, n) for n = (b - a) x (c - a).
struct Hit {
  double t;
  double d_dot_n;
};

inline std::optional<Hit> intersect(DVec o, DVec d, Vec3 a, Vec3 b, Vec3 c) {
  const DVec e1{double(b.x) - a.x, double(b.y) - a.y, double(b.z) - a.z};
  const DVec e2{double(c.x) - a.x, double(c.y) - a.y, double(c.z) - a.z};
  const DVec h{d.y * e2.z - d.z * e2.y, d.z * e2.x - d.x * e2.z, d.x * e2.y - d.y * e2.x};
  const double det = e1.x * h.x + e1.y * h.y + e1.z * h.z;
  if (det == 0.0) return std::nullopt;
  const double inv = 1.0 / det;
  const DVec s{o.x - a.x, o.y - a.y, o.z - a.z};
  const double u = (s.x * h.x + s.y * h.y + s.z * h.z) * inv;
  if (u < 0.0 || u > 1.0) return std::nullopt;
  const DVec q{s.y * e1.z - s.z * e1.y, s.z * e1.x - s.x * e1.z, s.x * e1.y - s.y * e1.x};
  const double v = (d.x * q.x + d.y * q.y + d.z * q.z) * inv;
  if (v < 0.0 || u + v > 1.0) return std::nullopt;
  const double t = (e2.x * q.x + e2.y * q.y + e2.z * q.z) * inv;
  if (!(t > 0.0)) return std::nullopt;
  const DVec n{e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x};
  return Hit{t, d.x * n.x + d.y * n.y + d.z * n.z};
}

}  // namespace caligo::testing
