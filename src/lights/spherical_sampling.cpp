#include "lights/spherical_sampling.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace caligo {
namespace {

constexpr double kPiD = std::numbers::pi;

struct D3 {
  double x = 0.0, y = 0.0, z = 0.0;
};
D3 d3(Vec3 v) { return {v.x, v.y, v.z}; }
D3 operator+(D3 a, D3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
D3 operator-(D3 a, D3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
D3 operator*(D3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dot(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 cross(D3 a, D3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double length(D3 a) { return std::sqrt(dot(a, a)); }
D3 normalize(D3 a) { return a * (1.0 / length(a)); }
Vec3 to_vec3(D3 a) { return {float(a.x), float(a.y), float(a.z)}; }
D3 load(const double* v) { return {v[0], v[1], v[2]}; }
void store(double* out, D3 v) {
  out[0] = v.x;
  out[1] = v.y;
  out[2] = v.z;
}
// The angle between unit vectors as a unit complex number (cos, sin): no trigonometry.
// Sums of angles are then products, and one atan2 gives the sum (the spherical excess).
struct Turn {
  double c = 1.0, s = 0.0;
};
Turn turn_between(D3 a, D3 b) { return {dot(a, b), length(cross(a, b))}; }
Turn operator*(Turn x, Turn y) { return {x.c * y.c - x.s * y.s, x.c * y.s + x.s * y.c}; }
// The angle of `t` in [0, 2 pi).
double angle_of(Turn t) {
  const double a = std::atan2(t.s, t.c);
  return a < 0.0 ? a + 2.0 * kPiD : a;
}
// The part of `v` perpendicular to the unit vector `w`, normalised.
D3 gram_schmidt(D3 v, D3 w) { return normalize(v - w * dot(v, w)); }

}  // namespace

double spherical_triangle_solid_angle(Vec3 receiver, Vec3 p0, Vec3 p1, Vec3 p2) {
  const D3 r = d3(receiver), a = d3(p0) - r, b = d3(p1) - r, c = d3(p2) - r;
  const double la = length(a), lb = length(b), lc = length(c);
  const double triple = std::abs(dot(a, cross(b, c)));
  const double denom = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
  return 2.0 * std::atan2(triple, denom);
}

SphericalTriangle make_spherical_triangle(Vec3 receiver, Vec3 p0, Vec3 p1, Vec3 p2) {
  SphericalTriangle t{};
  const D3 p = d3(receiver);
  store(t.receiver, p);
  store(t.v0, d3(p0));
  store(t.v1, d3(p1));
  store(t.v2, d3(p2));
  const D3 a = normalize(d3(p0) - p), b = normalize(d3(p1) - p), c = normalize(d3(p2) - p);
  store(t.a, a);
  store(t.b, b);
  store(t.c, c);
  D3 n_ab = cross(a, b), n_bc = cross(b, c), n_ca = cross(c, a);
  if (!(dot(n_ab, n_ab) > 0.0 && dot(n_bc, n_bc) > 0.0 && dot(n_ca, n_ca) > 0.0)) return t;
  n_ab = normalize(n_ab);
  n_bc = normalize(n_bc);
  n_ca = normalize(n_ca);
  const Turn alpha = turn_between(n_ab, n_ca * -1.0);
  const Turn beta = turn_between(n_bc, n_ab * -1.0);
  const Turn gamma = turn_between(n_ca, n_bc * -1.0);
  t.cos_alpha = alpha.c;
  t.sin_alpha = alpha.s;
  t.cos_ab = dot(a, b);
  // alpha + beta + gamma - pi: the product rotated by pi. A rounding just below zero wraps
  // to ~2 pi; both ends are outside the range the callers sample by solid angle.
  const Turn sum = alpha * beta * gamma;
  t.solid_angle = angle_of({-sum.c, -sum.s});
  return t;
}

// Arvo's algorithm: u.x chooses the sub-triangle (a, b, c') of area u.x * A, u.y the point on
// the arc from b to c'. The point on the planar triangle is where the direction meets it
// (barycentrics by Moller-Trumbore, clamped onto the triangle).
std::optional<Vec3> sample_spherical_triangle(const SphericalTriangle& t, Vec2 u) {
  if (!(t.solid_angle > 0.0)) return std::nullopt;
  const D3 a = load(t.a), b = load(t.b), c = load(t.c);
  // sin and cos of pi + u.x A, and of phi = (pi + u.x A) - alpha.
  const double sin_area = -std::sin(double(u.x) * t.solid_angle), cos_area = -std::cos(double(u.x) * t.solid_angle);
  const double cos_alpha = t.cos_alpha, sin_alpha = t.sin_alpha;
  const double sin_phi = sin_area * cos_alpha - cos_area * sin_alpha;
  const double cos_phi = cos_area * cos_alpha + sin_area * sin_alpha;
  const double k1 = cos_phi + cos_alpha;
  const double k2 = sin_phi - sin_alpha * t.cos_ab;
  const double denom = (k2 * sin_phi + k1 * cos_phi) * sin_alpha;
  if (denom == 0.0) return std::nullopt;
  const double cos_bp = std::clamp((k2 + (k2 * cos_phi - k1 * sin_phi) * cos_alpha) / denom, -1.0, 1.0);
  const double sin_bp = std::sqrt(std::max(0.0, 1.0 - cos_bp * cos_bp));
  const D3 cp = a * cos_bp + gram_schmidt(c, a) * sin_bp;
  const double cos_theta = 1.0 - double(u.y) * (1.0 - dot(cp, b));
  const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
  const D3 w = b * cos_theta + gram_schmidt(cp, b) * sin_theta;
  // Where w meets the triangle's plane, as barycentrics.
  const D3 v0 = load(t.v0), e1 = load(t.v1) - v0, e2 = load(t.v2) - v0;
  const D3 s1 = cross(w, e2);
  const double divisor = dot(s1, e1);
  if (divisor == 0.0) return std::nullopt;
  const D3 s = load(t.receiver) - v0;
  double b1 = std::clamp(dot(s, s1) / divisor, 0.0, 1.0);
  double b2 = std::clamp(dot(w, cross(s, e1)) / divisor, 0.0, 1.0);
  if (b1 + b2 > 1.0) {
    const double sum = b1 + b2;
    b1 /= sum;
    b2 /= sum;
  }
  return to_vec3(v0 + e1 * b1 + e2 * b2);
}

SphericalRectangle make_spherical_rectangle(Vec3 receiver, Vec3 corner, Vec3 edge1, Vec3 edge2) {
  SphericalRectangle r{};
  const D3 e1 = d3(edge1);
  const double ex_len = length(e1);
  const D3 x = e1 * (1.0 / ex_len);
  const D3 e2 = d3(edge2) - x * dot(d3(edge2), x);  // the component along edge1 is ignored
  const double ey_len = length(e2);
  const D3 y = e2 * (1.0 / ey_len);
  D3 z = cross(x, y);
  const D3 d = d3(corner) - d3(receiver);
  r.z0 = dot(d, z);
  if (r.z0 > 0.0) {  // z points away from the rectangle
    z = z * -1.0;
    r.z0 = -r.z0;
  }
  r.x0 = dot(d, x);
  r.y0 = dot(d, y);
  r.x1 = r.x0 + ex_len;
  r.y1 = r.y0 + ey_len;
  store(r.origin, d3(receiver));
  store(r.x, x);
  store(r.y, y);
  store(r.z, z);
  // Unit normals of the planes through the receiver and each edge (the paper's closed forms).
  const D3 n0 = normalize(D3{0.0, r.z0, -r.y0}), n1 = normalize(D3{-r.z0, 0.0, r.x1});
  const D3 n2 = normalize(D3{0.0, -r.z0, r.y1}), n3 = normalize(D3{r.z0, 0.0, -r.x0});
  const Turn g0 = turn_between(n0 * -1.0, n1), g1 = turn_between(n1 * -1.0, n2);
  const Turn g2 = turn_between(n2 * -1.0, n3), g3 = turn_between(n3 * -1.0, n0);
  r.b0 = n0.z;
  r.b1 = n2.z;
  // k = 2 pi - g2 - g3, kept as its cosine and sine; S = g0 + g1 + g2 + g3 - 2 pi.
  const Turn g23 = g2 * g3;
  r.cos_k = g23.c;
  r.sin_k = -g23.s;
  r.solid_angle = angle_of(g0 * g1 * g2 * g3);
  return r;
}

Vec3 sample_spherical_rectangle(const SphericalRectangle& r, Vec2 u) {
  // The column x = xu that splits off a fraction u.x of the solid angle.
  // au = u.x S + k, its cosine and sine by rotating (cos u.x S, sin u.x S) by k.
  const double us = double(u.x) * r.solid_angle, cos_us = std::cos(us), sin_us = std::sin(us);
  const double cos_au = cos_us * r.cos_k - sin_us * r.sin_k, sin_au = sin_us * r.cos_k + cos_us * r.sin_k;
  const double fu = (cos_au * r.b0 - r.b1) / sin_au;
  double cu = std::copysign(1.0, fu) / std::sqrt(fu * fu + r.b0 * r.b0);
  cu = std::clamp(cu, -1.0 + 1e-12, 1.0 - 1e-12);
  const double xu = std::clamp(-(cu * r.z0) / std::sqrt(1.0 - cu * cu), r.x0, r.x1);
  // Along the column, uniform in the sine of the elevation h.
  const double dd = std::sqrt(xu * xu + r.z0 * r.z0);
  const double h0 = r.y0 / std::sqrt(dd * dd + r.y0 * r.y0);
  const double h1 = r.y1 / std::sqrt(dd * dd + r.y1 * r.y1);
  const double hv = h0 + double(u.y) * (h1 - h0), hv2 = hv * hv;
  const double yv = hv2 < 1.0 - 1e-12 ? std::clamp(hv * dd / std::sqrt(1.0 - hv2), r.y0, r.y1) : r.y1;
  return to_vec3(load(r.origin) + load(r.x) * xu + load(r.y) * yv + load(r.z) * r.z0);
}

}  // namespace caligo
