#include "hybrid/airlight.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace caligo {
namespace {

constexpr double kHalfPiD = std::numbers::pi / 2.0;
constexpr float kHalfPiF = float(kHalfPiD);

// Adaptive Simpson (Lyness' refinement) to an absolute tolerance, with at least `min_depth`
// levels of bisection so a narrow feature between the first samples cannot be missed.
template <class Fn>
double simpson_step(const Fn& f, double a, double b, double fa, double fm, double fb, double whole,
                    double eps, int depth, int min_depth) {
  const double m = 0.5 * (a + b), lm = 0.5 * (a + m), rm = 0.5 * (m + b);
  const double flm = f(lm), frm = f(rm);
  const double left = (m - a) / 6.0 * (fa + 4.0 * flm + fm);
  const double right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
  const double delta = left + right - whole;
  if (depth >= 40 || (depth >= min_depth && std::abs(delta) <= 15.0 * eps))
    return left + right + delta / 15.0;
  // Halving the tolerance stops at depth 20, so rounding noise in the integrand (exp of a
  // large argument) cannot drive the recursion to every leaf of depth 40.
  const double child_eps = depth < 20 ? 0.5 * eps : eps;
  return simpson_step(f, a, m, fa, flm, fm, left, child_eps, depth + 1, min_depth) +
         simpson_step(f, m, b, fm, frm, fb, right, child_eps, depth + 1, min_depth);
}

template <class Fn>
double adaptive_simpson(const Fn& f, double a, double b, double eps, int min_depth) {
  if (!(b > a)) return 0.0;
  const double fa = f(a), fm = f(0.5 * (a + b)), fb = f(b);
  return simpson_step(f, a, b, fa, fm, fb, (b - a) / 6.0 * (fa + 4.0 * fm + fb), eps, 0, min_depth);
}

// The grids are uniform in y^(1/4) for y = u / (1 + u) and y = (π/2 - v) / (π/2): near u = 0,
// v = π/2 H is nearly homogeneous (H ≈ x φ(u / x), x = π/2 - v), so what bounds the bilinear
// error there is the *relative* spacing, which the fourth root keeps small down to u, x ~ 1e-4.
float root4(float y) { return std::sqrt(std::sqrt(y)); }
double pow4(double y) { return (y * y) * (y * y); }

// π/2 - ξ(t) = ½ atan2(h, x) for h > 0, x = t - D cos γ, with the arctangent as Abramowitz and
// Stegun's 4.4.49 polynomial on [0, 1] (|error| <= 1e-5 rad, below the tables' error): std::atan2
// was half the cost of a march step.
float half_angle(float h, float x) {
  const float ax = std::abs(x);
  const bool steep = h > ax;
  const float z = steep ? ax / h : (ax > 0.0f ? h / ax : 0.0f), z2 = z * z;
  float a = z * (0.9998660f + z2 * (-0.3302995f + z2 * (0.1801410f + z2 * (-0.0851330f + z2 * 0.0208351f))));
  if (steep) a = 0.5f * kPi - a;
  if (x < 0.0f) a = kPi - a;
  return 0.5f * a;
}

// tan ξ - tan v without cancellation near π/2 (both huge).
double tan_difference(double xi, double v) { return std::sin(xi - v) / (std::cos(xi) * std::cos(v)); }

// ∫_{v0}^{v1} e^{-u (tan ξ - tan v0)} dξ.
double scaled_cell(double u, double v0, double v1, double eps, int min_depth) {
  if (u == 0.0) return v1 - v0;
  return adaptive_simpson([&](double xi) { return std::exp(-u * tan_difference(xi, v0)); }, v0, v1, eps,
                          min_depth);
}

}  // namespace

double airlight_F_quadrature(double u, double v) {
  v = std::clamp(v, 0.0, kHalfPiD);
  if (u <= 0.0) return v;
  return adaptive_simpson([&](double xi) { return std::exp(-u * std::tan(xi)); }, 0.0, v, 1e-12, 6);
}

double airlight_H_quadrature(double u, double v) {
  v = std::clamp(v, 0.0, kHalfPiD);
  return scaled_cell(std::max(u, 0.0), v, kHalfPiD, 1e-12, 6);
}

AirlightTable::AirlightTable(Options options)
    : nu_(std::max(options.u_samples, 3)), nv_(std::max(options.v_samples, 3)) {
  e_.assign(size_t(nu_) * size_t(nv_), 0.0f);
  std::vector<double> v(nv_);  // column j: q = j / (nv - 1), v = π/2 (1 - (1 - q)^4)
  for (int j = 0; j < nv_; ++j)
    v[j] = j == nv_ - 1 ? kHalfPiD : kHalfPiD * (1.0 - pow4(1.0 - double(j) / (nv_ - 1)));
  for (int i = 0; i < nu_; ++i) {
    float* row = e_.data() + size_t(i) * nv_;
    row[nv_ - 1] = 0.0f;  // H(u, π/2) = 0
    if (i == nu_ - 1) {   // u = ∞: (1 + u) H(u, v) -> 1 / (1 + tan² v)
      for (int j = 0; j + 1 < nv_; ++j) row[j] = float(std::pow(std::cos(v[j]), 2.0));
      continue;
    }
    const double y = pow4(double(i) / (nu_ - 1)), u = y / (1.0 - y);
    // H(v_j) = ∫_{v_j}^{v_{j+1}} + e^{-u (tan v_{j+1} - tan v_j)} H(v_{j+1}): every factor <= 1, so
    // the sweep from H(π/2) = 0 downwards neither overflows nor loses precision.
    double h = 0.0;
    for (int j = nv_ - 2; j >= 0; --j) {
      h = scaled_cell(u, v[j], v[j + 1], 1e-12, 1) + std::exp(-u * tan_difference(v[j + 1], v[j])) * h;
      row[j] = float((1.0 + u) * h);
    }
  }
}

const AirlightTable& AirlightTable::shared() {
  static const AirlightTable table;
  return table;
}

AirlightTable::Row AirlightTable::row(float u) const {
  Row r;
  float a = 0.0f;
  if (u > 1e12f) {  // also +∞; NaN and negatives read as 0
    a = 1.0f;
    r.inv_one_plus_u = 0.0f;
  } else if (u > 0.0f) {
    a = root4(u / (1.0f + u));
    r.inv_one_plus_u = 1.0f / (1.0f + u);
  }
  const float fa = a * float(nu_ - 1);
  const int i = std::min(int(fa), nu_ - 2);
  r.lo = e_.data() + size_t(i) * nv_;
  r.hi = r.lo + nv_;
  r.weight = fa - float(i);
  return r;
}

float AirlightTable::H_complement(const Row& r, float x) const {
  const float q = 1.0f - root4(std::clamp(x * (1.0f / kHalfPiF), 0.0f, 1.0f));  // NaN reads as x = 0
  const float fq = q * float(nv_ - 1);
  const int j = std::clamp(int(fq), 0, nv_ - 2);
  const float t = fq - float(j);
  const float lo = r.lo[j] + t * (r.lo[j + 1] - r.lo[j]);
  const float hi = r.hi[j] + t * (r.hi[j + 1] - r.hi[j]);
  return (lo + r.weight * (hi - lo)) * r.inv_one_plus_u;
}

float AirlightTable::H(float u, float v) const {
  return H_complement(row(u), float(kHalfPiD - std::clamp(double(v), 0.0, kHalfPiD)));
}

float AirlightTable::F(float u, float v) const {
  u = u > 0.0f ? u : 0.0f;
  const double vd = std::clamp(double(v), 0.0, kHalfPiD);
  const Row r = row(u);
  const double decay = std::exp(-double(u) * std::tan(vd));
  return float(std::max(
      0.0, double(H_complement(r, kHalfPiF)) - decay * double(H_complement(r, float(kHalfPiD - vd)))));
}

AirlightRay make_airlight_ray(const AirlightTable& table, const AirlightMedium& medium, float intensity,
                              float light_distance, float cos_gamma, float min_distance) {
  const float d = std::max(light_distance, min_distance);
  const float c = std::clamp(cos_gamma, -1.0f, 1.0f);
  const float s = std::sqrt(std::max(0.0f, 1.0f - c * c));
  AirlightRay ray;
  ray.sigma_t = std::max(medium.sigma_t, 0.0f);
  ray.along = d * c;
  ray.h = std::max(d * s, min_distance);
  ray.a1 = ray.sigma_t * ray.h;
  ray.scale = std::max(medium.sigma_s, 0.0f) * std::max(intensity, 0.0f) / (2.0f * kPi * ray.h);
  ray.row = table.row(ray.a1);
  return ray;
}

AirlightRay make_airlight_ray(const AirlightTable& table, const AirlightMedium& medium, float intensity,
                              Vec3 light, Vec3 eye, Vec3 dir, float min_distance) {
  const Vec3 to_light = light - eye;
  const float d = length(to_light);
  const float c = d > 0.0f ? dot(dir, to_light) / d : 0.0f;
  return make_airlight_ray(table, medium, intensity, d, c, min_distance);
}

float airlight_tail(const AirlightTable& table, const AirlightRay& ray, float t) {
  if (!(t < kInfinity)) return 0.0f;
  t = std::clamp(t, 0.0f, 1e18f);  // beyond, d(t)² would overflow; T there is below float's range anyway
  const float x = t - ray.along;
  const float d = std::sqrt(ray.h * ray.h + x * x);
  const float path = ray.sigma_t > 0.0f ? ray.sigma_t * (t + d) : 0.0f;
  return ray.scale * std::exp(-path) * table.H_complement(ray.row, half_angle(ray.h, x));  // π/2 - ξ(t)
}

float airlight_interval(const AirlightTable& table, const AirlightRay& ray, float t0, float t1) {
  t0 = std::max(t0, 0.0f);
  if (!(t1 > t0)) return 0.0f;
  return std::max(0.0f, airlight_tail(table, ray, t0) - airlight_tail(table, ray, t1));
}

// ---------------------------------------------------------------------------------------------

FrameAirlight::FrameAirlight(const AirlightTable& table, const AirlightMedium& medium, float intensity,
                             Vec3 light, Vec3 eye, Options options)
    : light_(light),
      eye_(eye),
      distance_(std::max(length(light - eye), options.min_distance)),
      min_distance_(options.min_distance),
      ng_(std::max(options.gamma_samples, 3)),
      nw_(std::max(options.w_samples, 3)) {
  const float sigma_t = std::max(medium.sigma_t, 0.0f);
  scale_ = std::max(medium.sigma_s, 0.0f) * std::max(intensity, 0.0f) * std::exp(-sigma_t * distance_) /
           (2.0f * kPi);
  p_.assign(size_t(ng_) * size_t(nw_), 0.0f);
  // P(γ, w) = H(A1, γ/2) - e^{-A1 (tan ξ - tan γ/2)} H(A1, ξ), from the H table (differences of
  // the scaled tail), kept non-decreasing along w so an interval is never negative.
  for (int i = 0; i < ng_; ++i) {
    // Rows uniform in r, γ = π (3r² - 2r³): quadratic at both ends, where A1 ∝ sin γ -> 0 and
    // P has A1 ln A1 behaviour (as F does in u) that uniform γ rows resolve badly.
    const double g = double(i) / (ng_ - 1);
    const double gamma = std::numbers::pi * g * g * (3.0 - 2.0 * g), half = 0.5 * gamma;
    const float a1 = float(sigma_t * distance_ * std::max(0.0, std::sin(gamma)));
    const AirlightTable::Row r = table.row(a1);
    const double h0 = table.H_complement(r, float(kHalfPiD - half));
    float* row = p_.data() + size_t(i) * nw_;
    float running = 0.0f;
    for (int j = 1; j < nw_; ++j) {
      const double w = 1.0 - pow4(1.0 - double(j) / (nw_ - 1));
      const double xi = (j == nw_ - 1) ? kHalfPiD : half + (kHalfPiD - half) * w;
      const double p =
          h0 - std::exp(-a1 * tan_difference(xi, half)) * table.H_complement(r, float(kHalfPiD - xi));
      running = std::max(running, float(p));
      row[j] = running;
    }
  }
}

FrameAirlight::Ray FrameAirlight::ray(Vec3 dir) const {
  const Vec3 to_light = light_ - eye_;
  const float d = length(to_light);
  return ray_cos(d > 0.0f ? dot(dir, to_light) / d : 0.0f);
}

FrameAirlight::Ray FrameAirlight::ray_cos(float cos_gamma) const {
  const float c = std::clamp(cos_gamma, -1.0f, 1.0f);
  const float s = std::sqrt(std::max(0.0f, 1.0f - c * c));
  Ray r;
  r.along = distance_ * c;
  r.h = std::max(distance_ * s, min_distance_);
  // π/2 - γ/2 = π/2 - ξ(0) of the clamped geometry, so w(0) = 0 exactly.
  const float range = half_angle(r.h, -r.along);
  if (range > 1e-7f) r.inv_range = 1.0f / range;
  const float y = std::clamp(1.0f - 2.0f * range / kPi, 0.0f, 1.0f);                       // γ / π
  const float fg = (0.5f - std::sin(std::asin(1.0f - 2.0f * y) / 3.0f)) * float(ng_ - 1);  // smoothstep⁻¹
  const int i = std::min(int(fg), ng_ - 2);
  r.lo = p_.data() + size_t(i) * nw_;
  r.hi = r.lo + nw_;
  r.weight = fg - float(i);
  r.scale = scale_ / r.h;
  return r;
}

float FrameAirlight::cumulative(const Ray& r, float t) const {
  t = std::max(t, 0.0f);  // t = ∞: atan2 = 0, w = 1
  // 1 - w = (π/2 - ξ(t)) / (π/2 - γ/2), and q = 1 - (1 - w)^(1/4) indexes the columns.
  const float one_minus_w = std::clamp(half_angle(r.h, t - r.along) * r.inv_range, 0.0f, 1.0f);
  const float fq = (1.0f - root4(one_minus_w)) * float(nw_ - 1);
  const int j = std::min(int(fq), nw_ - 2);
  const float f = fq - float(j);
  const float lo = r.lo[j] + f * (r.lo[j + 1] - r.lo[j]);
  const float hi = r.hi[j] + f * (r.hi[j + 1] - r.hi[j]);
  return lo + r.weight * (hi - lo);
}

float FrameAirlight::interval(const Ray& r, float t0, float t1) const {
  if (!(t1 > t0)) return 0.0f;
  return std::max(0.0f, r.scale * (cumulative(r, t1) - cumulative(r, t0)));
}

}  // namespace caligo
