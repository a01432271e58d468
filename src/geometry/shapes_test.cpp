#include "geometry/shapes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace caligo {
namespace {

Vec3 triangle_normal(const TriangleMesh& m, size_t t) {
  const Vec3 p0 = m.positions[m.indices[3 * t]];
  return cross(m.positions[m.indices[3 * t + 1]] - p0, m.positions[m.indices[3 * t + 2]] - p0);
}

TEST(BoxMesh, TrianglesFaceOutwardsAndCoverTheSurface) {
  const TriangleMesh box = box_mesh({-1, -2, -3}, {1, 2, 3});
  ASSERT_EQ(box.triangle_count(), 12u);
  float area = 0.0f;
  for (size_t t = 0; t < box.triangle_count(); ++t) {
    const Vec3 n = triangle_normal(box, t);
    const Vec3 p0 = box.positions[box.indices[3 * t]];
    const Vec3 centroid =
        (p0 + box.positions[box.indices[3 * t + 1]] + box.positions[box.indices[3 * t + 2]]) / 3.0f;
    EXPECT_GT(dot(n, centroid), 0.0f) << "triangle " << t << " faces inwards";
    area += 0.5f * length(n);
  }
  EXPECT_FLOAT_EQ(area, 2.0f * (2 * 4 + 2 * 6 + 4 * 6));
}

TEST(RectangleMesh, NormalFollowsEdgeOrder) {
  const TriangleMesh r = rectangle_mesh({0, 0, 0}, {1, 0, 0}, {0, 0, -1});
  ASSERT_EQ(r.triangle_count(), 2u);
  for (size_t t = 0; t < 2; ++t) EXPECT_GT(normalize(triangle_normal(r, t)).y, 0.999f);
}

TEST(Sphere, RootsMatchTheAnalyticDistances) {
  const Sphere s = Sphere::make({0, 0, 10}, 2.0f, {});
  const auto roots = intersect_sphere(s, {{0, 0, 0}, {0, 0, 1}});
  ASSERT_TRUE(roots);
  EXPECT_NEAR(roots->t0, 8.0f, 1e-5f);
  EXPECT_NEAR(roots->t1, 12.0f, 1e-5f);
  EXPECT_FALSE(intersect_sphere(s, {{0, 2.01f, 0}, {0, 0, 1}}));
}

TEST(Sphere, FarOriginKeepsPrecision) {
  const Sphere s = Sphere::make({0, 0, 0}, 1.0f, {});
  const auto roots = intersect_sphere(s, {{0, 0.5f, -1e4f}, {0, 0, 1}});
  ASSERT_TRUE(roots);
  EXPECT_NEAR(roots->t0, 1e4f - std::sqrt(0.75f), 2e-3f);
}

TEST(Sphere, NonUniformScaleMakesAnEllipsoid) {
  const Sphere s = Sphere::make({0, 0, 0}, 1.0f, Transform::scale({3, 1, 1}));
  const auto along_x = intersect_sphere(s, {{-10, 0, 0}, {1, 0, 0}});
  ASSERT_TRUE(along_x);
  EXPECT_NEAR(along_x->t0, 7.0f, 1e-5f);
  const Vec3 n = sphere_normal(s, {3, 0, 0});
  EXPECT_NEAR(n.x, 1.0f, 1e-5f);
  // On the ellipse x^2/9 + y^2 = 1 the normal is proportional to (x/9, y).
  const Vec3 p(3 * std::cos(0.7f), std::sin(0.7f), 0);
  const Vec3 expected = normalize(Vec3(p.x / 9, p.y, 0));
  EXPECT_NEAR(dot(sphere_normal(s, p), expected), 1.0f, 1e-5f);
  const Bounds3 b = s.world_bounds();
  EXPECT_NEAR(b.hi.x, 3.0f, 1e-5f);
  EXPECT_NEAR(b.hi.y, 1.0f, 1e-5f);
}

}  // namespace
}  // namespace caligo
