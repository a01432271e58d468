#include "geometry/mesh_closure.h"

#include <gtest/gtest.h>

#include "geometry/mesh_generate.h"
#include "geometry/shapes.h"

namespace caligo {
namespace {

// A tetrahedron with outward winding; each vertex appears once.
TriangleMesh tetrahedron() {
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.indices = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  return m;
}

TEST(MeshClosure, TetrahedronIsClosed) { EXPECT_TRUE(check_closure(tetrahedron()).closed()); }

TEST(MeshClosure, GeneratedAndBoxMeshesAreClosed) {
  EXPECT_TRUE(check_closure(icosphere(2)).closed());
  EXPECT_TRUE(check_closure(torus_knot({.segments = 32, .sides = 6})).closed());
  EXPECT_TRUE(check_closure(box_mesh({0, 0, 0}, {1, 2, 3})).closed());
}

TEST(MeshClosure, SplitVerticesAreWelded) {
  TriangleMesh m = tetrahedron();
  // Give the last triangle its own copies of its corners (a UV seam).
  for (int k = 0; k < 3; ++k) {
    m.positions.push_back(m.positions[m.indices[9 + k]]);
    m.indices[9 + k] = uint32_t(m.positions.size() - 1);
  }
  EXPECT_TRUE(check_closure(m).closed());
}

TEST(MeshClosure, MissingTriangleLeavesThreeBoundaryEdges) {
  TriangleMesh m = tetrahedron();
  m.indices.resize(9);
  const MeshClosure c = check_closure(m);
  EXPECT_FALSE(c.closed());
  EXPECT_EQ(c.boundary_edges, 3u);
  EXPECT_EQ(check_closure(rectangle_mesh({0, 0, 0}, {1, 0, 0}, {0, 1, 0})).boundary_edges, 4u);
}

TEST(MeshClosure, FlippedTriangleIsMisoriented) {
  TriangleMesh m = tetrahedron();
  std::swap(m.indices[10], m.indices[11]);
  const MeshClosure c = check_closure(m);
  EXPECT_FALSE(c.closed());
  EXPECT_EQ(c.boundary_edges, 0u);
  EXPECT_EQ(c.misoriented_edges, 3u);
}

TEST(MeshClosure, ThirdTriangleOnAnEdgeIsNonManifold) {
  TriangleMesh m = tetrahedron();
  m.positions.push_back({1, 1, 1});
  m.indices.insert(m.indices.end(), {0, 1, 4});
  EXPECT_GE(check_closure(m).non_manifold_edges, 1u);
}

}  // namespace
}  // namespace caligo
