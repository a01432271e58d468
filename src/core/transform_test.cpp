// Transforms against hand-computed results, and the identities they must satisfy.
#include "core/transform.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/rng.h"

namespace caligo {
namespace {

constexpr float kEps = 1e-5f;

void expect_vec_near(Vec3 a, Vec3 b, float eps = kEps) {
  EXPECT_NEAR(a.x, b.x, eps);
  EXPECT_NEAR(a.y, b.y, eps);
  EXPECT_NEAR(a.z, b.z, eps);
}

void expect_identity(const Mat4& m, float eps = kEps) {
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) EXPECT_NEAR(m.m[i][j], i == j ? 1.0f : 0.0f, eps) << i << "," << j;
}

// A transform mixing all the kinds, with non-uniform scale.
Transform composite() {
  return Transform::translate({1.0f, -2.0f, 3.0f}) * Transform::rotate(0.7f, {1.0f, 2.0f, -0.5f}) *
         Transform::scale({2.0f, 0.5f, 3.0f});
}

}  // namespace

TEST(Transform, TranslateMovesPointsNotVectorsOrNormals) {
  const Transform t = Transform::translate({1.0f, 2.0f, 3.0f});
  expect_vec_near(t.point({1.0f, 1.0f, 1.0f}), {2.0f, 3.0f, 4.0f});
  expect_vec_near(t.vector({1.0f, 1.0f, 1.0f}), {1.0f, 1.0f, 1.0f});
  expect_vec_near(t.normal({0.0f, 0.0f, 1.0f}), {0.0f, 0.0f, 1.0f});
}

TEST(Transform, ScaleScalesPointsAndVectorsInverselyScalesNormals) {
  const Transform s = Transform::scale({2.0f, 3.0f, 4.0f});
  expect_vec_near(s.point({1.0f, 1.0f, 1.0f}), {2.0f, 3.0f, 4.0f});
  expect_vec_near(s.vector({1.0f, -1.0f, 0.5f}), {2.0f, -3.0f, 2.0f});
  expect_vec_near(s.normal({1.0f, 1.0f, 1.0f}), {0.5f, 1.0f / 3.0f, 0.25f});
}

TEST(Transform, RotateAboutAxes) {
  const Transform rz = Transform::rotate(kPi / 2.0f, {0.0f, 0.0f, 1.0f});
  expect_vec_near(rz.point({1.0f, 0.0f, 0.0f}), {0.0f, 1.0f, 0.0f});
  expect_vec_near(rz.vector({0.0f, 1.0f, 0.0f}), {-1.0f, 0.0f, 0.0f});
  expect_vec_near(rz.normal({1.0f, 0.0f, 0.0f}), {0.0f, 1.0f, 0.0f});      // rotations keep normals
  const Transform rx = Transform::rotate(kPi / 2.0f, {2.0f, 0.0f, 0.0f});  // axis need not be unit
  expect_vec_near(rx.point({0.0f, 1.0f, 0.0f}), {0.0f, 0.0f, 1.0f});
  // A third of a turn about (1,1,1) cycles the axes.
  const Transform r111 = Transform::rotate(2.0f * kPi / 3.0f, {1.0f, 1.0f, 1.0f});
  expect_vec_near(r111.vector({1.0f, 0.0f, 0.0f}), {0.0f, 1.0f, 0.0f});
}

TEST(Transform, CompositionAppliesRightOperandFirst) {
  const Transform t = Transform::translate({1.0f, 0.0f, 0.0f}) * Transform::scale({2.0f, 2.0f, 2.0f});
  expect_vec_near(t.point({1.0f, 1.0f, 1.0f}), {3.0f, 2.0f, 2.0f});
}

TEST(Transform, InverseTimesTransformIsIdentity) {
  const Transform t = composite();
  expect_identity((t.inverse() * t).matrix());
  expect_identity((t * t.inverse()).matrix());
  expect_identity(t.matrix() * t.inverse_matrix());
  const Vec3 p{0.3f, -1.2f, 4.0f};
  expect_vec_near(t.inverse().point(t.point(p)), p, 1e-4f);
}

TEST(Transform, IdentityIsIdentity) {
  EXPECT_TRUE(Transform().is_identity());
  EXPECT_FALSE(Transform::translate({0.0f, 0.0f, 1.0f}).is_identity());
}

TEST(Mat4, InverseOfSingularIsNullopt) {
  Mat4 zero;
  EXPECT_FALSE(zero.inverse().has_value());
  Mat4 rank2 = Mat4::identity();
  rank2.m[2] = {1.0f, 1.0f, 0.0f, 0.0f};
  rank2.m[1] = {2.0f, 2.0f, 0.0f, 0.0f};
  EXPECT_FALSE(rank2.inverse().has_value());
  Mat4 flat = Mat4::identity();
  flat.m[2][2] = 0.0f;  // projects onto the z = 0 plane
  EXPECT_FALSE(flat.inverse().has_value());
}

TEST(Mat4, InverseOfGeneralMatrix) {
  const Mat4 m = composite().matrix();
  const auto inv = m.inverse();
  ASSERT_TRUE(inv.has_value());
  expect_identity(m * *inv);
  expect_identity(*inv * m);
}

TEST(Transform, FromMatrixAcceptsAffine) {
  const auto t = Transform::from_matrix(composite().matrix());
  ASSERT_TRUE(t.has_value());
  expect_identity(t->matrix() * t->inverse_matrix());
}

TEST(Transform, FromMatrixRejectsNonAffineSingularAndNaN) {
  Mat4 projective = Mat4::identity();
  projective.m[3][2] = 1.0f;
  EXPECT_FALSE(Transform::from_matrix(projective).has_value());
  Mat4 w_scaled = Mat4::identity();
  w_scaled.m[3][3] = 2.0f;
  EXPECT_FALSE(Transform::from_matrix(w_scaled).has_value());
  Mat4 nan = Mat4::identity();
  nan.m[0][3] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_FALSE(Transform::from_matrix(nan).has_value());
  Mat4 inf = Mat4::identity();
  inf.m[1][1] = kInfinity;
  EXPECT_FALSE(Transform::from_matrix(inf).has_value());
  Mat4 singular = Mat4::identity();
  singular.m[0][0] = 0.0f;
  EXPECT_FALSE(Transform::from_matrix(singular).has_value());
}

// Under non-uniform scale a normal transformed by the matrix itself would tilt; the inverse
// transpose keeps it perpendicular to every transformed tangent.
TEST(Transform, NormalStaysPerpendicularToTangent) {
  const Transform t = composite();
  Pcg32 rng;
  for (int n = 0; n < 100; ++n) {
    const Vec3 normal =
        normalize(Vec3(rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float() - 0.5f));
    const Frame frame = Frame::from_z(normal);
    const Vec3 nt = normalize(t.normal(normal));
    EXPECT_NEAR(dot(nt, normalize(t.vector(frame.s))), 0.0f, 1e-5f);
    EXPECT_NEAR(dot(nt, normalize(t.vector(frame.t))), 0.0f, 1e-5f);
  }
}

TEST(Transform, LookAtMapsZToViewDirection) {
  const Vec3 eye{1.0f, 2.0f, 3.0f}, target{4.0f, 6.0f, 3.0f}, up{0.0f, 0.0f, 1.0f};
  const Transform t = Transform::look_at(eye, target, up);
  expect_vec_near(t.point({0.0f, 0.0f, 0.0f}), eye);
  expect_vec_near(t.vector({0.0f, 0.0f, 1.0f}), normalize(target - eye));
  expect_vec_near(t.point({0.0f, 0.0f, 5.0f}), target);  // |target - eye| = 5
  // Local +Y leans towards `up` and stays perpendicular to the view direction.
  const Vec3 y = t.vector({0.0f, 1.0f, 0.0f});
  EXPECT_GT(dot(y, up), 0.99f);
  EXPECT_NEAR(dot(y, normalize(target - eye)), 0.0f, kEps);
  EXPECT_NEAR(length(t.vector({1.0f, 0.0f, 0.0f})), 1.0f, kEps);  // no scaling
}

TEST(Transform, SwapsHandednessOnlyForMirrors) {
  EXPECT_TRUE(Transform::scale({-1.0f, 1.0f, 1.0f}).swaps_handedness());
  EXPECT_TRUE(Transform::scale({-1.0f, -1.0f, -1.0f}).swaps_handedness());
  EXPECT_FALSE(Transform::scale({-1.0f, -1.0f, 1.0f}).swaps_handedness());  // a half turn
  EXPECT_FALSE(composite().swaps_handedness());
  EXPECT_FALSE(Transform::translate({1.0f, 2.0f, 3.0f}).swaps_handedness());
}

TEST(Transform, BoundsOfTransformedBox) {
  Bounds3 box;
  box.extend({0.0f, 0.0f, 0.0f});
  box.extend({1.0f, 2.0f, 3.0f});
  const Bounds3 moved =
      (Transform::translate({1.0f, 1.0f, 1.0f}) * Transform::scale({2.0f, 1.0f, -1.0f})).bounds(box);
  expect_vec_near(moved.lo, {1.0f, 1.0f, -2.0f});
  expect_vec_near(moved.hi, {3.0f, 3.0f, 1.0f});
  // A quarter turn about z swaps the x and y extents.
  const Bounds3 turned = Transform::rotate(kPi / 2.0f, {0.0f, 0.0f, 1.0f}).bounds(box);
  expect_vec_near(turned.lo, {-2.0f, 0.0f, 0.0f});
  expect_vec_near(turned.hi, {0.0f, 1.0f, 3.0f});
  EXPECT_TRUE(composite().bounds(Bounds3{}).empty());
}

TEST(Transform, RayTransformsOriginAndDirection) {
  const Transform t = Transform::translate({0.0f, 0.0f, 1.0f}) * Transform::scale({2.0f, 2.0f, 2.0f});
  const Ray r = t.ray({{1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 0.5f, 10.0f});
  expect_vec_near(r.origin, {2.0f, 0.0f, 1.0f});
  expect_vec_near(r.direction, {0.0f, 2.0f, 0.0f});
  EXPECT_EQ(r.tmin, 0.5f);
  EXPECT_EQ(r.tmax, 10.0f);
}

}  // namespace caligo
