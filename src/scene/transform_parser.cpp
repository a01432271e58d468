#include "scene/transform_parser.h"

#include <cmath>

#include <nlohmann/json.hpp>

#include "core/math.h"

namespace caligo {

Vec3 read_direction(const JsonCursor& c) {
  const Vec3 v = c.vec3();
  if (!(length_squared(v) > 0.0f)) c.fail("expected a non-zero direction, got " + c.describe());
  return normalize(v);
}

namespace {

Transform parse_rotation(const JsonCursor& c) {
  ObjectReader r(c, "a rotation");
  r.allow({"angle", "axis"});
  const float angle = r.number("angle");
  const Vec3 axis = read_direction(r.required("axis"));
  r.finish();
  return Transform::rotate(radians(angle), axis);
}

Transform parse_scale(const JsonCursor& c) {
  const Vec3 s = c.is_number() ? Vec3(c.number()) : c.vec3();
  if (s.x == 0.0f || s.y == 0.0f || s.z == 0.0f)
    c.fail("expected non-zero scale factors, got " + c.describe() + " (it would flatten the object)");
  for (int a = 0; a < 3; ++a)
    if (std::abs(s[a]) < 1e-6f || std::abs(s[a]) > 1e6f)
      c.fail("expected scale factors of magnitude in [1e-06, 1e+06], got " + c.describe());
  return Transform::scale(s);
}

Transform parse_matrix(const JsonCursor& c) {
  if (!c.is_array() || c.json().size() != 16)
    c.fail("expected an array of 16 numbers (a row-major 4x4 matrix), got " + c.describe());
  const auto e = c.elements("");
  Mat4 m;
  for (int i = 0; i < 16; ++i) m.m[i / 4][i % 4] = e[i].number();
  const auto& last = m.m[3];
  if (last[0] != 0.0f || last[1] != 0.0f || last[2] != 0.0f || last[3] != 1.0f)
    c.fail("expected the last row to be [0, 0, 0, 1] (an affine transform), got [" + format_number(last[0]) +
           ", " + format_number(last[1]) + ", " + format_number(last[2]) + ", " + format_number(last[3]) +
           "]");
  auto t = Transform::from_matrix(m);
  if (!t) c.fail("expected an invertible matrix, got a singular one");
  return *t;
}

Transform parse_transform_op(const JsonCursor& c) {
  ObjectReader r(c, "a transform operation");
  r.allow({"translate", "rotate", "scale", "matrix"});
  if (c.json().size() != 1)
    r.fail("expected exactly one of translate, rotate, scale, matrix in a transform operation, got " +
           c.describe());
  if (auto v = r.optional("translate")) return Transform::translate(v->vec3());
  if (auto v = r.optional("rotate")) return parse_rotation(*v);
  if (auto v = r.optional("scale")) return parse_scale(*v);
  return parse_matrix(r.required("matrix"));
}

}  // namespace

// Operations apply in the order written: [op1, op2, ...] gives ... * op2 * op1.
Transform parse_transform(const JsonCursor& c) {
  Transform t;
  for (const JsonCursor& op : c.elements("an array of transform operations")) t = parse_transform_op(op) * t;
  if (!Transform::from_matrix(t.matrix()))
    c.fail("expected an invertible transform, got one whose composed matrix is singular");
  return t;
}

BoxCorners read_box_corners(ObjectReader& r) {
  const Vec3 lo = r.vec3("min");
  const JsonCursor hi_c = r.required("max");
  const Vec3 hi = hi_c.vec3();
  if (!(hi.x > lo.x && hi.y > lo.y && hi.z > lo.z))
    hi_c.fail("expected max > min in every component (min is " + format_vec3(lo) + "), got " +
              hi_c.describe());
  const Vec3 extent = hi - lo;
  for (int a = 0; a < 3; ++a)
    if (!size_range().contains(extent[a]))
      hi_c.fail("expected a box extent " + size_range().describe() + " m in every axis, got " +
                format_vec3(extent));
  return {lo, hi};
}

}  // namespace caligo
