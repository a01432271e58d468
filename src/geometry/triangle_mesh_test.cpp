#include "geometry/triangle_mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace caligo {
namespace {

// Unit right triangle in the z = 0 plane, counter-clockwise seen from +z.
TriangleMesh make_triangle() {
  TriangleMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.indices = {0, 1, 2};
  return mesh;
}

Vec3 geometric_normal(const TriangleMesh& mesh, size_t t) {
  const Vec3 p0 = mesh.positions[mesh.indices[3 * t]];
  const Vec3 p1 = mesh.positions[mesh.indices[3 * t + 1]];
  const Vec3 p2 = mesh.positions[mesh.indices[3 * t + 2]];
  return normalize(cross(p1 - p0, p2 - p0));
}

void expect_near(Vec3 a, Vec3 b, float tolerance = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, tolerance);
  EXPECT_NEAR(a.y, b.y, tolerance);
  EXPECT_NEAR(a.z, b.z, tolerance);
}

TEST(ValidateMesh, AcceptsAValidMesh) {
  EXPECT_EQ(validate_mesh(make_triangle()), "");
  TriangleMesh with_normals = make_triangle();
  with_normals.normals.assign(3, Vec3(0, 0, 1));
  EXPECT_EQ(validate_mesh(with_normals), "");
}

TEST(ValidateMesh, RejectsAnEmptyMesh) {
  EXPECT_EQ(validate_mesh(TriangleMesh{}), "mesh has no triangles");
  TriangleMesh no_triangles = make_triangle();
  no_triangles.indices.clear();
  EXPECT_EQ(validate_mesh(no_triangles), "mesh has no triangles");
}

TEST(ValidateMesh, RejectsAnIndexCountThatIsNotAMultipleOfThree) {
  TriangleMesh mesh = make_triangle();
  mesh.indices.push_back(0);
  EXPECT_EQ(validate_mesh(mesh), "mesh has 4 indices, which is not a multiple of 3");
}

TEST(ValidateMesh, RejectsAnIndexOutOfRange) {
  TriangleMesh mesh = make_triangle();
  mesh.indices.insert(mesh.indices.end(), {0, 2, 99});
  EXPECT_EQ(validate_mesh(mesh), "triangle 1 refers to vertex 99, but the mesh has 3 vertices");
}

TEST(ValidateMesh, RejectsNonFinitePositions) {
  for (float bad : {std::numeric_limits<float>::quiet_NaN(), kInfinity, -kInfinity}) {
    TriangleMesh mesh = make_triangle();
    mesh.positions[2].z = bad;
    EXPECT_EQ(validate_mesh(mesh), "vertex 2 has a non-finite coordinate");
  }
}

TEST(ValidateMesh, RejectsNormalsThatDoNotMatchThePositions) {
  TriangleMesh mesh = make_triangle();
  mesh.normals.assign(2, Vec3(0, 0, 1));
  EXPECT_EQ(validate_mesh(mesh), "mesh has 2 normals for 3 vertices (needs none or one per vertex)");
}

TEST(ValidateMesh, RejectsNonFiniteNormals) {
  TriangleMesh mesh = make_triangle();
  mesh.normals.assign(3, Vec3(0, 0, 1));
  mesh.normals[1].x = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(validate_mesh(mesh), "normal 1 has a non-finite coordinate");
}

TEST(ValidateMesh, RejectsRepeatedIndices) {
  TriangleMesh mesh = make_triangle();
  mesh.indices.insert(mesh.indices.end(), {1, 2, 1});
  EXPECT_EQ(validate_mesh(mesh), "triangle 1 is degenerate (zero area)");
}

TEST(ValidateMesh, RejectsZeroAreaTriangles) {
  TriangleMesh collinear = make_triangle();
  collinear.positions[2] = {0.5f, 0, 0};
  EXPECT_EQ(validate_mesh(collinear), "triangle 0 is degenerate (zero area)");

  // Distinct indices of coincident vertices.
  TriangleMesh coincident = make_triangle();
  coincident.positions[1] = coincident.positions[0];
  EXPECT_EQ(validate_mesh(coincident), "triangle 0 is degenerate (zero area)");

  // Collinear far from the origin (all coordinates exactly representable).
  TriangleMesh far_away;
  far_away.positions = {{1e6f, 2e6f, 3e6f}, {1e6f + 1, 2e6f + 2, 3e6f + 3}, {1e6f + 3, 2e6f + 6, 3e6f + 9}};
  far_away.indices = {0, 1, 2};
  EXPECT_EQ(validate_mesh(far_away), "triangle 0 is degenerate (zero area)");
}

TEST(ValidateMesh, AcceptsThinButNonDegenerateTriangles) {
  TriangleMesh sliver = make_triangle();
  sliver.positions[2] = {0.5f, 1e-6f, 0};
  EXPECT_EQ(validate_mesh(sliver), "");
  TriangleMesh tiny = make_triangle();
  for (Vec3& p : tiny.positions) p *= 1e-15f;  // small but well-shaped
  EXPECT_EQ(validate_mesh(tiny), "");
}

TEST(ValidateMesh, ReportsTheFirstProblemByKind) {
  // Structural problems come before geometric ones, so the message names the root cause.
  TriangleMesh mesh = make_triangle();
  mesh.positions[0].x = std::numeric_limits<float>::quiet_NaN();
  mesh.indices.insert(mesh.indices.end(), {0, 0, 0});
  EXPECT_EQ(validate_mesh(mesh), "vertex 0 has a non-finite coordinate");
}

TEST(TransformMesh, TransformsPositions) {
  TriangleMesh mesh = make_triangle();
  transform_mesh(mesh, Transform::translate({1, 2, 3}) * Transform::scale({2, 2, 2}));
  expect_near(mesh.positions[0], {1, 2, 3});
  expect_near(mesh.positions[1], {3, 2, 3});
  expect_near(mesh.positions[2], {1, 4, 3});
  EXPECT_EQ(mesh.indices, (std::vector<uint32_t>{0, 1, 2}));
}

TEST(TransformMesh, TransformsNormalsWithTheInverseTransposeAndNormalises) {
  // A 45-degree plane x + y = 1 with its unit normal; a non-uniform scale tilts the normal
  // differently from the surface, which only the inverse transpose gets right.
  TriangleMesh mesh;
  mesh.positions = {{1, 0, 0}, {0, 1, 0}, {0, 1, 1}};
  mesh.indices = {0, 1, 2};
  mesh.normals.assign(3, normalize(Vec3(1, 1, 0)));
  transform_mesh(mesh, Transform::scale({4, 1, 1}));
  // Scaled plane: x / 4 + y = 1, whose normal is (1/4, 1, 0).
  for (Vec3 n : mesh.normals) {
    expect_near(n, normalize(Vec3(0.25f, 1, 0)));
    EXPECT_NEAR(length(n), 1.0f, 1e-6f);
  }
  // The shading normal stays perpendicular to the transformed surface.
  EXPECT_NEAR(dot(mesh.normals[0], mesh.positions[1] - mesh.positions[0]), 0.0f, 1e-5f);
}

TEST(TransformMesh, KeepsNormalsUnitLengthUnderUniformScale) {
  TriangleMesh mesh = make_triangle();
  mesh.normals.assign(3, Vec3(0, 0, 1));
  transform_mesh(mesh, Transform::scale({10, 10, 10}));
  for (Vec3 n : mesh.normals) expect_near(n, {0, 0, 1});
}

TEST(TransformMesh, MirroringFlipsWindingSoTheGeometricNormalFollowsTheShadingNormal) {
  TriangleMesh mesh = make_triangle();
  mesh.normals.assign(3, Vec3(0, 0, 1));
  expect_near(geometric_normal(mesh, 0), {0, 0, 1});

  // Mirror in z: the outward normal becomes -z. Without the winding flip, the geometric
  // normal of the transformed vertices would still be +z.
  transform_mesh(mesh, Transform::scale({1, 1, -1}));
  EXPECT_EQ(mesh.indices, (std::vector<uint32_t>{0, 2, 1}));
  for (Vec3 n : mesh.normals) expect_near(n, {0, 0, -1});
  expect_near(geometric_normal(mesh, 0), {0, 0, -1});
}

TEST(TransformMesh, MirroringInTheTrianglePlaneAlsoFlipsTheNormal) {
  // Mirror in x (in the triangle's plane): the geometric normal of the mirrored, reordered
  // triangle must agree with the transformed shading normal, which stays +z.
  TriangleMesh mesh = make_triangle();
  mesh.normals.assign(3, Vec3(0, 0, 1));
  transform_mesh(mesh, Transform::rotate(0.3f, {1, 2, 3}) * Transform::scale({-1, 1, 1}));
  const Vec3 n = mesh.normals[0];
  expect_near(geometric_normal(mesh, 0), n);
}

TEST(TransformMesh, ARotationKeepsWindingAndNormalsConsistent) {
  TriangleMesh mesh = make_triangle();
  mesh.normals.assign(3, Vec3(0, 0, 1));
  transform_mesh(mesh, Transform::rotate(1.1f, {0.3f, -1, 0.5f}));
  EXPECT_EQ(mesh.indices, (std::vector<uint32_t>{0, 1, 2}));
  expect_near(geometric_normal(mesh, 0), mesh.normals[0]);
}

TEST(TransformMesh, LeavesZeroNormalsZeroInsteadOfNaN) {
  TriangleMesh mesh = make_triangle();
  mesh.normals.assign(3, Vec3(0, 0, 0));
  transform_mesh(mesh, Transform::scale({2, 3, 4}));
  for (Vec3 n : mesh.normals) EXPECT_EQ(n, Vec3(0, 0, 0));
}

}  // namespace
}  // namespace caligo
