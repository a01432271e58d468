#include "geometry/mesh_generate.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <stdexcept>
#include <utility>

#include "core/math.h"

namespace caligo {
namespace {

// The vertex half way along an edge, pushed onto the sphere; shared by both triangles of the
// edge so the subdivided mesh stays welded.
uint32_t midpoint(TriangleMesh& mesh, std::map<std::pair<uint32_t, uint32_t>, uint32_t>& cache, uint32_t a,
                  uint32_t b) {
  const auto key = std::minmax(a, b);
  if (const auto it = cache.find(key); it != cache.end()) return it->second;
  const uint32_t index = uint32_t(mesh.positions.size());
  mesh.positions.push_back(normalize((mesh.positions[a] + mesh.positions[b]) * 0.5f));
  cache.emplace(key, index);
  return index;
}

}  // namespace

TriangleMesh icosphere(int subdivisions) {
  if (subdivisions < 0 || subdivisions > 9) throw std::invalid_argument("icosphere: subdivisions outside [0, 9]");
  const float t = (1.0f + std::sqrt(5.0f)) * 0.5f;
  TriangleMesh mesh;
  for (const Vec3 v : {Vec3(-1, t, 0), Vec3(1, t, 0), Vec3(-1, -t, 0), Vec3(1, -t, 0), Vec3(0, -1, t), Vec3(0, 1, t),
                       Vec3(0, -1, -t), Vec3(0, 1, -t), Vec3(t, 0, -1), Vec3(t, 0, 1), Vec3(-t, 0, -1), Vec3(-t, 0, 1)})
    mesh.positions.push_back(normalize(v));
  mesh.indices = {0, 11, 5, 0, 5,  1, 0, 1, 7, 0, 7,  10, 0, 10, 11, 1, 5, 9, 5, 11, 4,  11, 10, 2,  10, 7, 6, 7, 1, 8,
                  3, 9,  4, 3, 4,  2, 3, 2, 6, 3, 6,  8,  3, 8,  9,  4, 9, 5, 2, 4,  11, 6,  2,  10, 8,  6, 7, 9, 8, 1};
  for (int level = 0; level < subdivisions; ++level) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> cache;
    std::vector<uint32_t> next;
    next.reserve(mesh.indices.size() * 4);
    for (size_t i = 0; i < mesh.indices.size(); i += 3) {
      const uint32_t a = mesh.indices[i], b = mesh.indices[i + 1], c = mesh.indices[i + 2];
      const uint32_t ab = midpoint(mesh, cache, a, b), bc = midpoint(mesh, cache, b, c),
                     ca = midpoint(mesh, cache, c, a);
      next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    mesh.indices = std::move(next);
  }
  mesh.normals = mesh.positions;  // the unit sphere's normal is its position
  return mesh;
}

TriangleMesh torus_knot(const TorusKnot& k) {
  if (k.p < 1 || k.q < 1 || std::gcd(k.p, k.q) != 1 || k.segments < 3 || k.sides < 3)
    throw std::invalid_argument("torus_knot: p, q must be coprime and >= 1, segments and sides >= 3");
  // The centre curve and its derivative at parameter s in [0, 2 pi).
  const auto curve = [&](float s) {
    const float r = k.major + k.minor * std::cos(float(k.q) * s);
    return Vec3(r * std::cos(float(k.p) * s), k.minor * std::sin(float(k.q) * s), r * std::sin(float(k.p) * s));
  };
  TriangleMesh mesh;
  mesh.positions.reserve(size_t(k.segments) * size_t(k.sides));
  for (int i = 0; i < k.segments; ++i) {
    const float s = 2.0f * kPi * float(i) / float(k.segments), ds = 1e-3f;
    const Vec3 c = curve(s);
    const Vec3 tangent = normalize(curve(s + ds) - curve(s - ds));
    // A frame from the curve's offset to the torus core circle: never parallel to the tangent
    // for a knot on a torus, so the tube does not twist abruptly.
    const Vec3 towards_core = c - Vec3(k.major * std::cos(float(k.p) * s), 0.0f, k.major * std::sin(float(k.p) * s));
    const Vec3 normal = normalize(towards_core - tangent * dot(towards_core, tangent));
    const Vec3 binormal = cross(tangent, normal);
    for (int j = 0; j < k.sides; ++j) {
      const float a = 2.0f * kPi * float(j) / float(k.sides);
      mesh.positions.push_back(c + (normal * std::cos(a) + binormal * std::sin(a)) * k.tube);
    }
  }
  const auto at = [&](int i, int j) { return uint32_t((i % k.segments) * k.sides + (j % k.sides)); };
  for (int i = 0; i < k.segments; ++i)
    for (int j = 0; j < k.sides; ++j) {
      const uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      // Winding chosen so the geometric normal points out of the tube (checked by the tests).
      mesh.indices.insert(mesh.indices.end(), {a, c, b, a, d, c});
    }
  return mesh;
}

int icosphere_subdivisions_for(uint64_t triangles) {
  int n = 0;
  for (uint64_t count = 20; count < triangles && n < 9; count *= 4) ++n;
  return n;
}

TorusKnot torus_knot_for(uint64_t triangles) {
  TorusKnot k;
  // 2 * (16 s) * s = 32 s^2 triangles.
  const uint64_t target = std::min<uint64_t>(std::max<uint64_t>(triangles, 32 * 9), uint64_t(1) << 24);
  k.sides = std::max(3, int(std::ceil(std::sqrt(double(target) / 32.0))));
  k.segments = 16 * k.sides;
  return k;
}

}  // namespace caligo
