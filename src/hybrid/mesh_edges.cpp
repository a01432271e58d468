// Welding, edge classification and silhouette extraction.
#include "hybrid/mesh_edges.h"

#include <algorithm>
#include <cstring>
#include <sstream>
#include <unordered_map>

namespace caligo {
namespace {

// Exact-position key: the bit patterns of the coordinates, with -0 folded onto +0 so the
// two zeros weld.
struct PositionKey {
  uint32_t bits[3];
  friend bool operator==(const PositionKey&, const PositionKey&) = default;
};

PositionKey key_of(Vec3 p) {
  PositionKey k;
  for (int i = 0; i < 3; ++i) {
    const float v = p[i] + 0.0f;  // -0 + 0 = +0
    std::memcpy(&k.bits[i], &v, sizeof v);
  }
  return k;
}

struct PositionHash {
  size_t operator()(const PositionKey& k) const {
    uint64_t h = 1469598103934665603ull;
    for (uint32_t b : k.bits) h = (h ^ b) * 1099511628211ull;
    return size_t(h ^ (h >> 29));
  }
};

// One triangle's traversal of an undirected edge (lo, hi).
struct HalfEdge {
  uint32_t lo, hi;
  uint32_t tri;
  bool forward;  // traversed lo -> hi
};

std::string format_point(Vec3 p) {
  std::ostringstream s;
  s << '(' << p.x << ", " << p.y << ", " << p.z << ')';
  return s.str();
}

// Welds positions that are equal (bit for bit): `vertices` gets each once; returns, for every
// input position, its welded index.
std::vector<uint32_t> weld_positions(const TriangleMesh& mesh, std::vector<Vec3>& vertices) {
  std::unordered_map<PositionKey, uint32_t, PositionHash> welded;
  welded.reserve(mesh.positions.size());
  std::vector<uint32_t> remap(mesh.positions.size());
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const auto [it, inserted] = welded.try_emplace(key_of(mesh.positions[i]), uint32_t(vertices.size()));
    if (inserted) vertices.push_back(mesh.positions[i]);
    remap[i] = it->second;
  }
  return remap;
}

// Sorting half-edges by their undirected key groups each edge's triangles together
// (cheaper and smaller than a hash map of vectors for meshes of a million triangles).
std::vector<HalfEdge> sorted_half_edges(const std::vector<std::array<uint32_t, 3>>& triangles) {
  std::vector<HalfEdge> half;
  half.reserve(3 * triangles.size());
  for (uint32_t t = 0; t < uint32_t(triangles.size()); ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = triangles[t][size_t(k)], b = triangles[t][size_t((k + 1) % 3)];
      half.push_back({std::min(a, b), std::max(a, b), t, a < b});
    }
  std::sort(half.begin(), half.end(), [](const HalfEdge& x, const HalfEdge& y) {
    return x.lo != y.lo ? x.lo < y.lo : (x.hi != y.hi ? x.hi < y.hi : x.tri < y.tri);
  });
  return half;
}

}  // namespace

MeshEdges::MeshEdges(const TriangleMesh& mesh) {
  const std::vector<uint32_t> remap = weld_positions(mesh, vertices_);
  triangles_.reserve(mesh.triangle_count());
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    const std::array<uint32_t, 3> tri{remap[mesh.indices[3 * t]], remap[mesh.indices[3 * t + 1]],
                                      remap[mesh.indices[3 * t + 2]]};
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0]) {
      ++dropped_;
      continue;
    }
    triangles_.push_back(tri);
  }
  const std::vector<HalfEdge> half = sorted_half_edges(triangles_);
  std::string first_boundary, first_non_manifold, first_misoriented;
  auto describe = [&](const HalfEdge& h) {
    return "from " + format_point(vertices_[h.lo]) + " to " + format_point(vertices_[h.hi]);
  };
  for (size_t i = 0; i < half.size();) {
    size_t j = i + 1;
    while (j < half.size() && half[j].lo == half[i].lo && half[j].hi == half[i].hi) ++j;
    const size_t n = j - i;
    if (n == 1) {
      if (boundary_++ == 0) first_boundary = describe(half[i]);
    } else if (n > 2) {
      if (non_manifold_++ == 0) first_non_manifold = describe(half[i]);
    } else if (half[i].forward == half[i + 1].forward) {
      if (misoriented_++ == 0) first_misoriented = describe(half[i]);
    } else {
      const HalfEdge& f = half[i].forward ? half[i] : half[i + 1];
      const HalfEdge& b = half[i].forward ? half[i + 1] : half[i];
      edges_.push_back({{f.lo, f.hi}, {f.tri, b.tri}});
    }
    i = j;
  }
  describe_problems(first_boundary, first_non_manifold, first_misoriented);
}

void MeshEdges::describe_problems(const std::string& first_boundary, const std::string& first_non_manifold,
                                  const std::string& first_misoriented) {
  std::vector<std::string> problems;
  if (triangles_.empty()) problems.push_back("no triangles left after welding");
  if (boundary_ > 0)
    problems.push_back(std::to_string(boundary_) + " boundary edges (open mesh), first " + first_boundary);
  if (non_manifold_ > 0)
    problems.push_back(std::to_string(non_manifold_) +
                       " non-manifold edges (shared by 3+ triangles), first " + first_non_manifold);
  if (misoriented_ > 0)
    problems.push_back(std::to_string(misoriented_) + " edges with inconsistent winding, first " +
                       first_misoriented);
  for (size_t i = 0; i < problems.size(); ++i) problem_ += (i > 0 ? "; " : "") + problems[i];
}

bool faces_light(Vec3 p0, Vec3 p1, Vec3 p2, Vec3 light) {
  // Double precision: near the silhouette the dot product is a small difference of large
  // terms, and the two triangles of an edge must not both round to "facing".
  const double ax = double(p1.x) - p0.x, ay = double(p1.y) - p0.y, az = double(p1.z) - p0.z;
  const double bx = double(p2.x) - p0.x, by = double(p2.y) - p0.y, bz = double(p2.z) - p0.z;
  const double nx = ay * bz - az * by, ny = az * bx - ax * bz, nz = ax * by - ay * bx;
  return nx * (double(light.x) - p0.x) + ny * (double(light.y) - p0.y) + nz * (double(light.z) - p0.z) > 0.0;
}

Silhouette find_silhouette(const MeshEdges& mesh, Vec3 light) {
  Silhouette s;
  const auto& v = mesh.vertices();
  s.lit.resize(mesh.triangles().size());
  for (size_t t = 0; t < mesh.triangles().size(); ++t) {
    const auto& tri = mesh.triangles()[t];
    s.lit[t] = faces_light(v[tri[0]], v[tri[1]], v[tri[2]], light) ? 1 : 0;
    s.lit_count += s.lit[t];
  }
  for (const MeshEdge& e : mesh.edges()) {
    const bool lit0 = s.lit[e.tri[0]] != 0, lit1 = s.lit[e.tri[1]] != 0;
    if (lit0 == lit1) continue;
    // tri[0] traverses v0 -> v1; keep the lit triangle's direction.
    if (lit0)
      s.edges.push_back({e.v[0], e.v[1]});
    else
      s.edges.push_back({e.v[1], e.v[0]});
  }
  return s;
}

}  // namespace caligo
