#include "geometry/embree_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace caligo {
namespace {

TEST(EmbreeScene, RejectsNonFiniteVertices) {
  EmbreeScene scene;
  TriangleMesh mesh = rectangle_mesh({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  mesh.positions[2].y = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(scene.add_mesh(mesh), std::invalid_argument);
  mesh.positions[2].y = std::numeric_limits<float>::infinity();
  EXPECT_THROW(scene.add_mesh(mesh), std::invalid_argument);
  EXPECT_EQ(scene.geometry_count(), 0u);
}

TEST(EmbreeScene, ClosestHitOnATriangleAndASphere) {
  EmbreeScene scene;
  const uint32_t wall = scene.add_mesh(rectangle_mesh({-5, -5, 10}, {0, 10, 0}, {10, 0, 0}));
  const uint32_t ball = scene.add_sphere(Sphere::make({0, 0, 5}, 1.0f, {}));
  scene.commit();

  const auto hit = scene.intersect({{0, 0, 0}, {0, 0, 1}});
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->geom_id, ball);
  EXPECT_NEAR(hit->t, 4.0f, 1e-5f);
  EXPECT_NEAR(hit->ng.z, -1.0f, 1e-5f);

  const auto beside = scene.intersect({{3, 0, 0}, {0, 0, 1}});
  ASSERT_TRUE(beside);
  EXPECT_EQ(beside->geom_id, wall);
  EXPECT_NEAR(beside->t, 10.0f, 1e-5f);
  // cross(edge1, edge2) = cross(+y, +x) = -z: the wall faces the origin.
  EXPECT_NEAR(beside->ng.z, -1.0f, 1e-5f);

  EXPECT_FALSE(scene.intersect({{0, 0, 0}, {0, 0, -1}}));
  EXPECT_FALSE(scene.intersect({{0, 0, 0}, {0, 0, 1}, 0.0f, 3.9f}));
}

TEST(EmbreeScene, RayStartingInsideASphereHitsTheFarSide) {
  EmbreeScene scene;
  scene.add_sphere(Sphere::make({0, 0, 0}, 2.0f, {}));
  scene.commit();
  const auto hit = scene.intersect({{0, 0, 0}, {1, 0, 0}});
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 2.0f, 1e-5f);
  EXPECT_NEAR(hit->ng.x, 1.0f, 1e-5f);
}

TEST(EmbreeScene, OcclusionHonoursRangeAndShadowFlag) {
  EmbreeScene scene;
  const uint32_t glass = scene.add_mesh(rectangle_mesh({-1, -1, 2}, {2, 0, 0}, {0, 2, 0}));
  scene.add_sphere(Sphere::make({0, 0, 6}, 1.0f, {}));
  scene.commit();
  EXPECT_TRUE(scene.occluded({{0, 0, 0}, {0, 0, 1}, 0.0f, 3.0f}));
  EXPECT_FALSE(scene.occluded({{0, 0, 0}, {0, 0, 1}, 0.0f, 1.5f}));
  EXPECT_TRUE(scene.occluded({{0, 0, 3}, {0, 0, 1}, 0.0f, 10.0f}));  // the sphere

  scene.set_casts_shadows(glass, false);
  scene.commit();
  EXPECT_FALSE(scene.occluded({{0, 0, 0}, {0, 0, 1}, 0.0f, 3.0f}));
  EXPECT_TRUE(scene.occluded({{0, 0, 0}, {0, 0, 1}, 0.0f, 10.0f}));
  // Closest-hit queries still see it.
  EXPECT_EQ(scene.intersect({{0, 0, 0}, {0, 0, 1}})->geom_id, glass);
}

TEST(EmbreeScene, AllHitsAreSortedAndComplete) {
  EmbreeScene scene;
  const uint32_t box = scene.add_mesh(box_mesh({-1, -1, 2}, {1, 1, 4}));
  const uint32_t ball = scene.add_sphere(Sphere::make({0, 0, 3}, 0.5f, {}));
  const uint32_t far_ball = scene.add_sphere(Sphere::make({0, 0, 10}, 1.0f, {}));
  scene.commit();

  std::vector<SurfaceHit> hits;
  scene.all_hits({{0.1f, 0.05f, 0}, {0, 0, 1}}, hits);
  ASSERT_EQ(hits.size(), 6u);
  const uint32_t expected_ids[] = {box, ball, ball, box, far_ball, far_ball};
  for (size_t i = 0; i < hits.size(); ++i) {
    EXPECT_EQ(hits[i].geom_id, expected_ids[i]) << "hit " << i;
    if (i > 0) {
      EXPECT_LE(hits[i - 1].t, hits[i].t);
    }
  }
  EXPECT_NEAR(hits[0].t, 2.0f, 1e-5f);
  EXPECT_NEAR(hits[3].t, 4.0f, 1e-5f);
  EXPECT_NEAR(hits[5].t, 11.0f, 1e-2f);
  // The box's normals point out: towards the ray at entry, along it at exit.
  EXPECT_LT(hits[0].ng.z, 0.0f);
  EXPECT_GT(hits[3].ng.z, 0.0f);

  // A range that starts inside the box sees only what lies after tmin.
  scene.all_hits({{0.1f, 0.05f, 0}, {0, 0, 1}, 3.6f, 10.5f}, hits);
  ASSERT_EQ(hits.size(), 2u);
  EXPECT_EQ(hits[0].geom_id, box);
  EXPECT_EQ(hits[1].geom_id, far_ball);
}

TEST(EmbreeScene, BoundsCoverEverything) {
  EmbreeScene scene;
  scene.add_mesh(box_mesh({-1, -1, -1}, {1, 1, 1}));
  scene.add_sphere(Sphere::make({5, 0, 0}, 1.0f, {}));
  scene.commit();
  const Bounds3 b = scene.bounds();
  EXPECT_NEAR(b.hi.x, 6.0f, 1e-5f);
  EXPECT_NEAR(b.lo.x, -1.0f, 1e-5f);
}

}  // namespace
}  // namespace caligo
