// Affine transforms stored with their inverse, so points, vectors and normals all
// transform without inverting a matrix per call. Normals use the inverse transpose.
#pragma once

#include <array>
#include <optional>

#include "core/bounds.h"
#include "core/ray.h"
#include "core/vec.h"

namespace caligo {

struct Mat4 {
  // Row-major: m[row][col]; points are column vectors, so p' = M p.
  std::array<std::array<float, 4>, 4> m{};

  static Mat4 identity();
  friend Mat4 operator*(const Mat4& a, const Mat4& b);
  Mat4 transposed() const;
  // std::nullopt when the matrix is singular (or nearly so).
  std::optional<Mat4> inverse() const;
  bool operator==(const Mat4&) const = default;
};

class Transform {
 public:
  Transform() : m_(Mat4::identity()), inv_(Mat4::identity()) {}
  Transform(const Mat4& m, const Mat4& inv) : m_(m), inv_(inv) {}
  // std::nullopt if `m` is singular or not affine.
  static std::optional<Transform> from_matrix(const Mat4& m);

  static Transform translate(Vec3 d);
  static Transform scale(Vec3 s);  // requires non-zero components
  static Transform rotate(float angle_radians, Vec3 axis);
  // Camera-style frame: maps local +Z to (target - eye), +Y towards `up`.
  static Transform look_at(Vec3 eye, Vec3 target, Vec3 up);

  const Mat4& matrix() const { return m_; }
  const Mat4& inverse_matrix() const { return inv_; }
  Transform inverse() const { return {inv_, m_}; }
  bool is_identity() const { return m_ == Mat4::identity(); }
  // True when the transform flips orientation (negative determinant of the linear part).
  bool swaps_handedness() const;

  Vec3 point(Vec3 p) const;
  Vec3 vector(Vec3 v) const;
  Vec3 normal(Vec3 n) const;  // not normalised
  // The inverse transform applied directly (no Transform copy in hot loops).
  Vec3 inverse_point(Vec3 p) const;
  Vec3 inverse_vector(Vec3 v) const;
  Ray ray(const Ray& r) const { return {point(r.origin), vector(r.direction), r.tmin, r.tmax}; }
  Bounds3 bounds(const Bounds3& b) const;

  // `a * b` applies b first, then a.
  friend Transform operator*(const Transform& a, const Transform& b) {
    return {a.m_ * b.m_, b.inv_ * a.inv_};
  }

 private:
  Mat4 m_;
  Mat4 inv_;
};

}  // namespace caligo
