#include "core/transform.h"

#include <cmath>

namespace caligo {

Mat4 Mat4::identity() {
  Mat4 r;
  for (int i = 0; i < 4; ++i) r.m[i][i] = 1.0f;
  return r;
}

Mat4 operator*(const Mat4& a, const Mat4& b) {
  Mat4 r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      double s = 0.0;
      for (int k = 0; k < 4; ++k) s += double(a.m[i][k]) * double(b.m[k][j]);
      r.m[i][j] = float(s);
    }
  return r;
}

Mat4 Mat4::transposed() const {
  Mat4 r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) r.m[i][j] = m[j][i];
  return r;
}

// Gauss-Jordan elimination with partial pivoting, in double precision.
std::optional<Mat4> Mat4::inverse() const {
  double a[4][8];
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      a[i][j] = m[i][j];
      a[i][j + 4] = i == j ? 1.0 : 0.0;
    }
  double scale = 0.0;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) scale = std::fmax(scale, std::fabs(a[i][j]));
  if (!(scale > 0.0) || !std::isfinite(scale)) return std::nullopt;
  for (int col = 0; col < 4; ++col) {
    int pivot = col;
    for (int r = col + 1; r < 4; ++r)
      if (std::fabs(a[r][col]) > std::fabs(a[pivot][col])) pivot = r;
    if (std::fabs(a[pivot][col]) < 1e-12 * scale) return std::nullopt;
    if (pivot != col)
      for (int j = 0; j < 8; ++j) std::swap(a[pivot][j], a[col][j]);
    const double inv = 1.0 / a[col][col];
    for (int j = 0; j < 8; ++j) a[col][j] *= inv;
    for (int r = 0; r < 4; ++r) {
      if (r == col) continue;
      const double f = a[r][col];
      for (int j = 0; j < 8; ++j) a[r][j] -= f * a[col][j];
    }
  }
  Mat4 r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) r.m[i][j] = float(a[i][j + 4]);
  return r;
}

std::optional<Transform> Transform::from_matrix(const Mat4& m) {
  if (m.m[3][0] != 0.0f || m.m[3][1] != 0.0f || m.m[3][2] != 0.0f || m.m[3][3] != 1.0f) return std::nullopt;
  for (const auto& row : m.m)
    for (float v : row)
      if (!std::isfinite(v)) return std::nullopt;
  auto inv = m.inverse();
  if (!inv) return std::nullopt;
  return Transform(m, *inv);
}

Transform Transform::translate(Vec3 d) {
  Mat4 m = Mat4::identity(), inv = Mat4::identity();
  for (int i = 0; i < 3; ++i) {
    m.m[i][3] = d[i];
    inv.m[i][3] = -d[i];
  }
  return {m, inv};
}

Transform Transform::scale(Vec3 s) {
  Mat4 m = Mat4::identity(), inv = Mat4::identity();
  for (int i = 0; i < 3; ++i) {
    m.m[i][i] = s[i];
    inv.m[i][i] = 1.0f / s[i];
  }
  return {m, inv};
}

// Rodrigues' rotation about a unit axis; the inverse of a rotation is its transpose.
Transform Transform::rotate(float angle, Vec3 axis) {
  const Vec3 a = normalize(axis);
  const float s = std::sin(angle), c = std::cos(angle), t = 1.0f - c;
  Mat4 m = Mat4::identity();
  m.m[0][0] = a.x * a.x * t + c;
  m.m[0][1] = a.x * a.y * t - a.z * s;
  m.m[0][2] = a.x * a.z * t + a.y * s;
  m.m[1][0] = a.x * a.y * t + a.z * s;
  m.m[1][1] = a.y * a.y * t + c;
  m.m[1][2] = a.y * a.z * t - a.x * s;
  m.m[2][0] = a.x * a.z * t - a.y * s;
  m.m[2][1] = a.y * a.z * t + a.x * s;
  m.m[2][2] = a.z * a.z * t + c;
  return {m, m.transposed()};
}

Transform Transform::look_at(Vec3 eye, Vec3 target, Vec3 up) {
  const Vec3 forward = normalize(target - eye);
  const Vec3 right = normalize(cross(up, forward));
  const Vec3 new_up = cross(forward, right);
  Mat4 m = Mat4::identity();
  for (int i = 0; i < 3; ++i) {
    m.m[i][0] = right[i];
    m.m[i][1] = new_up[i];
    m.m[i][2] = forward[i];
    m.m[i][3] = eye[i];
  }
  return *from_matrix(m);
}

bool Transform::swaps_handedness() const {
  const auto& a = m_.m;
  const float det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                    a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                    a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  return det < 0.0f;
}

namespace {

Vec3 apply_point(const Mat4& m, Vec3 p) {
  const auto& a = m.m;
  return {a[0][0] * p.x + a[0][1] * p.y + a[0][2] * p.z + a[0][3],
          a[1][0] * p.x + a[1][1] * p.y + a[1][2] * p.z + a[1][3],
          a[2][0] * p.x + a[2][1] * p.y + a[2][2] * p.z + a[2][3]};
}

Vec3 apply_vector(const Mat4& m, Vec3 v) {
  const auto& a = m.m;
  return {a[0][0] * v.x + a[0][1] * v.y + a[0][2] * v.z, a[1][0] * v.x + a[1][1] * v.y + a[1][2] * v.z,
          a[2][0] * v.x + a[2][1] * v.y + a[2][2] * v.z};
}

}  // namespace

Vec3 Transform::point(Vec3 p) const { return apply_point(m_, p); }
Vec3 Transform::vector(Vec3 v) const { return apply_vector(m_, v); }
Vec3 Transform::inverse_point(Vec3 p) const { return apply_point(inv_, p); }
Vec3 Transform::inverse_vector(Vec3 v) const { return apply_vector(inv_, v); }

Vec3 Transform::normal(Vec3 n) const {
  const auto& b = inv_.m;  // transpose of the inverse
  return {b[0][0] * n.x + b[1][0] * n.y + b[2][0] * n.z, b[0][1] * n.x + b[1][1] * n.y + b[2][1] * n.z,
          b[0][2] * n.x + b[1][2] * n.y + b[2][2] * n.z};
}

Bounds3 Transform::bounds(const Bounds3& b) const {
  Bounds3 r;
  if (b.empty()) return r;
  for (int i = 0; i < 8; ++i)
    r.extend(point(b.corner(i)));
  return r;
}

}  // namespace caligo
