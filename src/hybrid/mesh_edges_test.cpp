#include "hybrid/mesh_edges.h"

#include <gtest/gtest.h>

#include <map>
#include <random>

#include "hybrid/shadow_volume_testing.h"

namespace caligo {
namespace {

using testing::box_mesh;
using testing::sphere_mesh;
using testing::torus_mesh;

double signed_volume(const MeshEdges& m) {
  double v = 0;
  for (const auto& t : m.triangles()) {
    const Vec3 a = m.vertices()[t[0]], b = m.vertices()[t[1]], c = m.vertices()[t[2]];
    v += double(dot(a, cross(b, c))) / 6.0;
  }
  return v;
}

TEST(MeshEdges, WeldsACubeOfSeparateFaces) {
  const MeshEdges m(box_mesh({-1, -1, -1}, {1, 1, 1}));
  EXPECT_EQ(m.vertices().size(), 8u);
  EXPECT_EQ(m.triangles().size(), 12u);
  EXPECT_EQ(m.edges().size(), 18u);  // Euler: V - E + F = 2
  EXPECT_TRUE(m.closed()) << m.problem();
  EXPECT_TRUE(m.problem().empty());
  EXPECT_NEAR(signed_volume(m), 8.0, 1e-5);
}

TEST(MeshEdges, ClosedSphereAndTorusSatisfyEuler) {
  const MeshEdges sphere(sphere_mesh({0, 0, 0}, 1.0f, 2));
  EXPECT_TRUE(sphere.closed()) << sphere.problem();
  EXPECT_EQ(sphere.triangles().size(), 320u);
  EXPECT_EQ(long(sphere.vertices().size()) - long(sphere.edges().size()) + long(sphere.triangles().size()),
            2);
  EXPECT_GT(signed_volume(sphere), 3.5);  // inscribed: a little below 4/3 pi
  const MeshEdges torus(torus_mesh({0, 0, 0}, 2.0f, 0.5f, 24, 12));
  EXPECT_TRUE(torus.closed()) << torus.problem();
  EXPECT_EQ(long(torus.vertices().size()) - long(torus.edges().size()) + long(torus.triangles().size()), 0);
  EXPECT_GT(signed_volume(torus), 0.0);
}

TEST(MeshEdges, WeldsSignedZeros) {
  TriangleMesh mesh = box_mesh({-1, -1, -1}, {0, 1, 1});  // x = 0 on the +x face
  for (Vec3& p : mesh.positions)
    if (p.x == 0.0f && p.y > 0.0f) p.x = -0.0f;  // some of the shared corners become -0
  EXPECT_TRUE(MeshEdges(mesh).closed());
}

TEST(MeshEdges, ReportsAnOpenMesh) {
  TriangleMesh mesh = box_mesh({0, 0, 0}, {1, 1, 1});
  mesh.indices.resize(mesh.indices.size() - 3);  // drop one triangle of the +z face
  const MeshEdges m(mesh);
  EXPECT_FALSE(m.closed());
  EXPECT_EQ(m.boundary_edge_count(), 3u);
  EXPECT_EQ(m.non_manifold_edge_count(), 0u);
  EXPECT_NE(m.problem().find("3 boundary edges"), std::string::npos) << m.problem();
  EXPECT_NE(m.problem().find("from ("), std::string::npos) << m.problem();
}

TEST(MeshEdges, ReportsNonManifoldAndMisorientedEdges) {
  TriangleMesh fin;  // three triangles on one edge
  testing::add_triangle(fin, {0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  testing::add_triangle(fin, {1, 0, 0}, {0, 0, 0}, {0, -1, 0});
  testing::add_triangle(fin, {1, 0, 0}, {0, 0, 0}, {0, 0, 1});
  const MeshEdges f(fin);
  EXPECT_EQ(f.non_manifold_edge_count(), 1u);
  EXPECT_FALSE(f.closed());
  EXPECT_NE(f.problem().find("non-manifold"), std::string::npos);

  TriangleMesh flipped = box_mesh({0, 0, 0}, {1, 1, 1});
  std::swap(flipped.indices[1], flipped.indices[2]);
  const MeshEdges m(flipped);
  EXPECT_EQ(m.misoriented_edge_count(), 3u);
  EXPECT_EQ(m.boundary_edge_count(), 0u);
  EXPECT_FALSE(m.closed());
}

TEST(MeshEdges, DropsTrianglesThatCollapseWhenWelded) {
  TriangleMesh mesh = box_mesh({0, 0, 0}, {1, 1, 1});
  testing::add_triangle(mesh, {0, 0, 0}, {0, 0, 0}, {1, 1, 1});
  const MeshEdges m(mesh);
  EXPECT_EQ(m.dropped_triangle_count(), 1u);
  EXPECT_TRUE(m.closed());
}

// The lit faces of a cube as seen from a light, counted analytically: the silhouette is the
// boundary of the lit faces; face diagonals never appear.
TEST(Silhouette, CubeEdgeCountsForLightsOnAFaceAnEdgeAndACorner) {
  const MeshEdges cube(box_mesh({-1, -1, -1}, {1, 1, 1}));
  const Silhouette face = find_silhouette(cube, {0.1f, 0.2f, 5.0f});
  EXPECT_EQ(face.lit_count, 2u);
  EXPECT_EQ(face.edges.size(), 4u);
  const Silhouette edge = find_silhouette(cube, {5.0f, 5.0f, 0.3f});
  EXPECT_EQ(edge.lit_count, 4u);
  EXPECT_EQ(edge.edges.size(), 6u);
  const Silhouette corner = find_silhouette(cube, {4.0f, 5.0f, 6.0f});
  EXPECT_EQ(corner.lit_count, 6u);
  EXPECT_EQ(corner.edges.size(), 6u);
  for (const auto& [a, b] : corner.edges) {
    // Every silhouette edge of the corner view is a cube edge (axis-aligned, length 2).
    EXPECT_FLOAT_EQ(length(cube.vertices()[a] - cube.vertices()[b]), 2.0f);
  }
  // The light inside the cube sees no face's front: nothing lit, no silhouette.
  const Silhouette inside = find_silhouette(cube, {0.1f, 0.2f, 0.3f});
  EXPECT_EQ(inside.lit_count, 0u);
  EXPECT_TRUE(inside.edges.empty());
}

// Brute force: every pair of triangles sharing two corner positions is an edge; it is a
// silhouette when one triangle's float normal faces the light and the other's does not.
// Each such edge, directed as the lit triangle runs it, must be found exactly once.
void expect_silhouette_matches_brute_force(const TriangleMesh& mesh, Vec3 light) {
  const MeshEdges edges(mesh);
  ASSERT_TRUE(edges.closed()) << edges.problem();
  const size_t n = mesh.triangle_count();
  auto corner = [&](size_t t, int k) { return mesh.positions[mesh.indices[3 * t + size_t(k)]]; };
  auto facing = [&](size_t t) {
    const Vec3 nrm = normalize(cross(corner(t, 1) - corner(t, 0), corner(t, 2) - corner(t, 0)));
    return dot(nrm, normalize(light - corner(t, 0)));
  };
  std::map<std::pair<std::array<float, 3>, std::array<float, 3>>, int> expected;
  for (size_t i = 0; i < n; ++i) {
    const float fi = facing(i);
    ASSERT_GT(std::abs(fi), 1e-4f) << "pick another light: triangle " << i << " is edge-on";
    if (fi <= 0.0f) continue;
    for (size_t j = 0; j < n; ++j) {
      if (j == i || facing(j) > 0.0f) continue;
      for (int k = 0; k < 3; ++k) {  // lit triangle i runs a -> b; does j contain both?
        const Vec3 a = corner(i, k), b = corner(i, (k + 1) % 3);
        bool has_a = false, has_b = false;
        for (int l = 0; l < 3; ++l) has_a |= corner(j, l) == a, has_b |= corner(j, l) == b;
        if (has_a && has_b) ++expected[{{a.x, a.y, a.z}, {b.x, b.y, b.z}}];
      }
    }
  }
  const Silhouette sil = find_silhouette(edges, light);
  std::map<std::pair<std::array<float, 3>, std::array<float, 3>>, int> found;
  std::map<uint32_t, int> balance;  // out - in per vertex
  for (const auto& [a, b] : sil.edges) {
    const Vec3 pa = edges.vertices()[a], pb = edges.vertices()[b];
    ++found[{{pa.x, pa.y, pa.z}, {pb.x, pb.y, pb.z}}];
    ++balance[a];
    --balance[b];
  }
  EXPECT_FALSE(expected.empty());
  EXPECT_EQ(found, expected);  // same edges, same directions, each exactly once
  for (const auto& [v, d] : balance) EXPECT_EQ(d, 0) << "silhouette loops not closed at vertex " << v;
}

TEST(Silhouette, MatchesBruteForceOnCubeSphereAndTorus) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const TriangleMesh meshes[] = {box_mesh({-1, -1, -1}, {1, 1, 1}), sphere_mesh({0, 0, 0}, 1.0f, 3),
                                 torus_mesh({0, 0, 0}, 2.0f, 0.6f, 24, 12)};
  for (const TriangleMesh& mesh : meshes)
    for (int i = 0; i < 4; ++i) {
      const Vec3 light = normalize(Vec3(u(rng), u(rng), u(rng))) * (4.0f + 3.0f * float(i));
      SCOPED_TRACE(::testing::Message() << "light " << light.x << " " << light.y << " " << light.z);
      expect_silhouette_matches_brute_force(mesh, light);
    }
}

// On a sphere the silhouette lies on the circle of tangency: angle acos(R / D) from the
// light's direction, up to the mesh's angular resolution.
TEST(Silhouette, SphereSilhouetteLiesOnTheTangencyCircle) {
  const MeshEdges sphere(sphere_mesh({0, 0, 0}, 1.0f, 4));  // edges span ~0.06 rad
  const Vec3 light{1.0f, 2.0f, 2.0f};                       // D = 3
  const Silhouette sil = find_silhouette(sphere, light);
  ASSERT_GT(sil.edges.size(), 50u);
  const float expected = std::acos(1.0f / 3.0f);
  for (const auto& [a, b] : sil.edges) {
    const Vec3 m = normalize(sphere.vertices()[a] + sphere.vertices()[b]);
    const float angle = std::acos(std::clamp(dot(m, normalize(light)), -1.0f, 1.0f));
    EXPECT_NEAR(angle, expected, 0.08f);
  }
}

}  // namespace
}  // namespace caligo
