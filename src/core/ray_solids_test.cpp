// The ray–solid tests of core/ray_solids.h against dense point membership along random rays.
#include "core/ray_solids.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/math.h"
#include "core/testing/random_rays.h"

namespace caligo {
namespace {

using testing::expect_matches_brute_force;
using testing::random_direction;
using testing::random_in_cube;

TEST(RaySolids, BallMatchesBruteForce) {
  Pcg32 rng(7, 1);
  int hits = 0;
  for (int ray = 0; ray < 300; ++ray) {
    const Vec3 c = random_in_cube(rng, 2.0f), o = random_in_cube(rng, 6.0f);
    const float r = 0.5f + 3.0f * rng.next_float();
    // Half the rays aim near the sphere (hits, grazing misses), half go anywhere.
    const Vec3 d = ray % 2 ? normalize(c + random_in_cube(rng, r * 1.2f) - o) : random_direction(rng);
    const float tmin = rng.next_float() * 2.0f, tmax = tmin + 15.0f * rng.next_float();
    const auto got = ray_ball(o, d, c, r, tmin, tmax);
    hits += got.has_value();
    expect_matches_brute_force([&](Vec3 p) { return length_squared(p - c) <= r * r; }, o, d, tmin, tmax, got,
                               ray);
  }
  EXPECT_GT(hits, 60);  // the random rays exercise both outcomes
  EXPECT_LT(hits, 290);
}

TEST(RaySolids, ConeMatchesBruteForce) {
  Pcg32 rng(11, 2);
  int hits = 0;
  for (int ray = 0; ray < 400; ++ray) {
    const Vec3 apex = random_in_cube(rng, 1.0f), axis = random_direction(rng);
    const float cos_half = std::cos(radians(5.0f + 80.0f * rng.next_float()));
    // Half the rays start near the apex: both nappes, the apex itself and grazing rays.
    const Vec3 o = ray % 2 ? apex + random_in_cube(rng, 0.5f) : random_in_cube(rng, 6.0f);
    const Vec3 d = random_direction(rng);
    const float tmin = 0.0f, tmax = 12.0f;
    const auto got = ray_cone(o, d, apex, axis, cos_half, tmin, tmax);
    hits += got.has_value();
    expect_matches_brute_force(
        [&](Vec3 p) {
          const Vec3 v = p - apex;
          return dot(v, axis) >= cos_half * length(v);
        },
        o, d, tmin, tmax, got, ray);
  }
  EXPECT_GT(hits, 80);
  EXPECT_LT(hits, 390);
}

TEST(RaySolids, OrientedBoxMatchesBruteForce) {
  Pcg32 rng(3, 4);
  int hits = 0;
  for (int ray = 0; ray < 300; ++ray) {
    const Vec3 z = random_direction(rng), y = normalize(cross(z, random_direction(rng)));
    const OrientedBox box{random_in_cube(rng, 1.0f), {cross(z, y), y, z}, -random_in_cube(rng, 0.2f) - Vec3(0.3f),
                          random_in_cube(rng, 0.2f) + Vec3(0.3f + 2.0f * rng.next_float())};
    const Vec3 o = random_in_cube(rng, 5.0f);
    const Vec3 d = ray % 2 ? normalize(box.origin + random_in_cube(rng, 1.5f) - o) : random_direction(rng);
    const auto got = ray_oriented_box(o, d, box, 0.0f, 12.0f);
    hits += got.has_value();
    expect_matches_brute_force(
        [&](Vec3 p) {
          for (int a = 0; a < 3; ++a) {
            const float u = dot(p - box.origin, box.axes[size_t(a)]);
            if (u < box.lo[a] || u > box.hi[a]) return false;
          }
          return true;
        },
        o, d, 0.0f, 12.0f, got, ray);
  }
  EXPECT_GT(hits, 40);
}

// A direction component of exactly 0 leaves its slab all (origin inside, faces included) or
// nothing, for either sign of zero.
TEST(RaySolids, BoxParallelToAFaceIsAllOrNothing) {
  const Vec3 lo(0.0f), hi(1.0f);
  for (float zero : {0.0f, -0.0f}) {
    const auto inside = ray_box({0.5f, 0.5f, -1.0f}, {zero, zero, 1.0f}, lo, hi, 0.0f, 10.0f);
    ASSERT_TRUE(inside);
    EXPECT_FLOAT_EQ(inside->t0, 1.0f);
    EXPECT_FLOAT_EQ(inside->t1, 2.0f);
    EXPECT_TRUE(ray_box({1.0f, 0.0f, -1.0f}, {zero, zero, 1.0f}, lo, hi, 0.0f, 10.0f));  // on two faces
    EXPECT_FALSE(ray_box({1.001f, 0.5f, -1.0f}, {zero, zero, 1.0f}, lo, hi, 0.0f, 10.0f));
  }
  EXPECT_FALSE(ray_box({0.5f, 0.5f, -1.0f}, {0, 0, 1}, lo, hi, 0.0f, 0.5f));  // ends before the box
}

// The sphere's roots are the unclipped line parameters, for a non-unit direction too.
TEST(RaySolids, SphereRootsOfANonUnitDirection) {
  const auto r = sphere_roots({-5, 0, 0}, {2, 0, 0}, {1, 0, 0}, 2.0f);
  ASSERT_TRUE(r);
  EXPECT_FLOAT_EQ(r->t0, 2.0f);
  EXPECT_FLOAT_EQ(r->t1, 4.0f);
  EXPECT_FALSE(sphere_roots({-5, 2.01f, 0}, {1, 0, 0}, {1, 0, 0}, 2.0f));
  EXPECT_FALSE(sphere_roots({-5, 0, 0}, {0, 0, 0}, {1, 0, 0}, 2.0f));
}

// The quadratic's pieces: two for an upward parabola with real roots, one for a downward one,
// the whole line or nothing without roots, and the linear case.
TEST(RaySolids, QuadraticPieces) {
  const QuadraticPieces up = quadratic_nonnegative(1, 0, -4);  // t^2 - 4 >= 0
  ASSERT_EQ(up.count, 2);
  EXPECT_DOUBLE_EQ(up.hi[0], -2.0);
  EXPECT_DOUBLE_EQ(up.lo[1], 2.0);
  const QuadraticPieces down = quadratic_nonnegative(-1, 0, 4);  // 4 - t^2 >= 0
  ASSERT_EQ(down.count, 1);
  EXPECT_DOUBLE_EQ(down.lo[0], -2.0);
  EXPECT_DOUBLE_EQ(down.hi[0], 2.0);
  EXPECT_EQ(quadratic_nonnegative(1, 0, 1).count, 1);   // always positive
  EXPECT_EQ(quadratic_nonnegative(-1, 0, -1).count, 0);  // never
  const QuadraticPieces linear = quadratic_nonnegative(0, 1, -2);  // 2 t - 2 >= 0
  ASSERT_EQ(linear.count, 1);
  EXPECT_DOUBLE_EQ(linear.lo[0], 1.0);
}

}  // namespace
}  // namespace caligo
