#include "geometry/mesh_generate.h"

#include <gtest/gtest.h>

#include <map>
#include <utility>

namespace caligo {
namespace {

Vec3 vertex(const TriangleMesh& m, size_t tri, int k) { return m.positions[m.indices[3 * tri + size_t(k)]]; }

// Closed, manifold and consistently oriented: every directed edge appears once and its
// reverse once (so every undirected edge has exactly two triangles, winding opposite ways).
void expect_closed_and_oriented(const TriangleMesh& m) {
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  for (size_t t = 0; t < m.triangle_count(); ++t)
    for (int k = 0; k < 3; ++k) ++directed[{m.indices[3 * t + size_t(k)], m.indices[3 * t + size_t((k + 1) % 3)]}];
  for (const auto& [edge, count] : directed) {
    ASSERT_EQ(count, 1) << "edge " << edge.first << "-" << edge.second << " repeated";
    ASSERT_EQ(directed.count({edge.second, edge.first}), 1u) << "edge " << edge.first << "-" << edge.second << " open";
  }
  EXPECT_EQ(validate_mesh(m), "");
}

TEST(MeshGenerate, IcosphereIsAClosedUnitSphereWithOutwardNormals) {
  for (int n : {0, 1, 3}) {
    const TriangleMesh m = icosphere(n);
    EXPECT_EQ(m.triangle_count(), size_t(20) << (2 * n));
    // Euler: V - E + F = 2 with E = 3F/2.
    EXPECT_EQ(int64_t(m.positions.size()) - int64_t(3 * m.triangle_count() / 2) + int64_t(m.triangle_count()), 2);
    for (const Vec3& p : m.positions) EXPECT_NEAR(length(p), 1.0f, 1e-5f);
    for (size_t t = 0; t < m.triangle_count(); ++t) {
      const Vec3 a = vertex(m, t, 0), b = vertex(m, t, 1), c = vertex(m, t, 2);
      EXPECT_GT(dot(cross(b - a, c - a), a + b + c), 0.0f) << "triangle " << t;
    }
    expect_closed_and_oriented(m);
  }
}

TEST(MeshGenerate, TorusKnotIsAClosedTubeWithOutwardNormals) {
  TorusKnot k;
  k.segments = 96;
  k.sides = 8;
  const TriangleMesh m = torus_knot(k);
  EXPECT_EQ(m.triangle_count(), size_t(2 * 96 * 8));
  expect_closed_and_oriented(m);
  // Outward: the normal points away from the tube's centre line, approximated by the ring's
  // centroid of the triangle's first vertex.
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    const uint32_t i0 = m.indices[3 * t];
    const size_t ring = i0 / uint32_t(k.sides);
    Vec3 centre;
    for (int j = 0; j < k.sides; ++j) centre += m.positions[ring * size_t(k.sides) + size_t(j)];
    centre = centre / float(k.sides);
    const Vec3 a = vertex(m, t, 0), b = vertex(m, t, 1), c = vertex(m, t, 2);
    EXPECT_GT(dot(cross(b - a, c - a), (a + b + c) / 3.0f - centre), 0.0f) << "triangle " << t;
  }
  EXPECT_THROW(torus_knot(TorusKnot{2, 4}), std::invalid_argument);  // not coprime
}

TEST(MeshGenerate, SizesForATriangleBudget) {
  EXPECT_EQ(icosphere_subdivisions_for(20), 0);
  EXPECT_EQ(icosphere_subdivisions_for(20000), 5);  // 20480
  const TorusKnot k = torus_knot_for(750000);
  const uint64_t n = uint64_t(2) * uint64_t(k.segments) * uint64_t(k.sides);
  EXPECT_GE(n, 750000u);
  EXPECT_LT(n, 800000u);
}

}  // namespace
}  // namespace caligo
