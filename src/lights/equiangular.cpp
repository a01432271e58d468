// Equiangular distance sampling (Kulla & Fajardo 2012), see equiangular.h.
//
// With x = t - delta the offset from the foot point, the density is uniform in the angle
// theta = atan(x / D) under which the light sees the ray point (hence "equiangular"):
//   pdf(t) = D / ((theta_b - theta_a)(D^2 + x^2)).
// Three regimes share one interface, chosen from the setup alone so that sample, pdf and
// invert always agree:
//  * Cauchy: the paper's form, for D > 0.
//  * Inverse square: D = 0, or D so small next to the nearer end of a segment that does not
//    contain the foot point (D <= 1e-6 |x_near|) that the angles are all within 1e-6 of
//    +-pi/2 and D^2 + x^2 = x^2 to 1e-12. Our derivation: pdf = 1 / (K x^2) with
//    K = 1/x_a - 1/x_b; the CDF is (1/x_a - 1/x) / K, inverted as x = 1 / (1/x_a - u K).
//    The scale is the nearer end, not the farther one: for [1, 1e7] with D = 1 the farther
//    end would call D negligible although the pdf near x = 1 is half the inverse-square
//    one (and an infinite b would call every D negligible).
//  * Uniform: D = 0 (or so small that the pdf overflows a float) with the foot point inside
//    [a, b]: the light lies on the segment, where 1/x^2 is not integrable. For an infinite b
//    this fallback has pdf 0, which callers already treat as "no sample".
// Work is in double: the angles of a distant or nearly collinear light crowd near +-pi/2,
// and differences of them are taken as one atan2 (the tan(A - B) identity) rather than by
// subtraction. b may be +infinity (a ray leaving the medium never): both non-uniform
// regimes integrate to infinity in closed form.
//
// Preconditions: a < b, D >= 0, all finite except possibly b. Pure and thread-safe.
#include "lights/equiangular.h"

#include <algorithm>
#include <cmath>

#include "core/math.h"

namespace caligo {
namespace {

constexpr double kCollinearRatio = 1e-6;

enum class Regime { kCauchy, kInverseSquare, kUniform };

struct Prepared {
  Regime regime;
  double a, b, delta, D;
  double xa;    // a - delta
  double span;  // Cauchy: theta_b - theta_a; inverse square: K = 1/x_a - 1/x_b; uniform: b - a
};

// atan(x1 / D) - atan(x0 / D) for x0 <= x1, without the cancellation of subtracting two
// angles near +-pi/2: tan(A - B) = D (x1 - x0) / (D^2 + x0 x1), and atan2 keeps the branch
// when the difference exceeds pi/2. For x1 = +inf it is pi/2 - atan(x0 / D) = atan2(D, x0).
double subtended_angle(double x0, double x1, double D) {
  if (std::isinf(x1)) return std::atan2(D, x0);
  return std::atan2(D * (x1 - x0), D * D + x0 * x1);
}

Prepared prepare(const EquiangularSetup& s) {
  Prepared p{Regime::kCauchy, s.a, s.b, s.delta, s.D, double(s.a) - s.delta, 0.0};
  const double xb = p.b - p.delta;
  const bool foot_outside = p.xa > 0.0 || xb < 0.0;
  if (foot_outside && p.D <= kCollinearRatio * std::min(std::abs(p.xa), std::abs(xb))) {
    p.regime = Regime::kInverseSquare;
    p.span = 1.0 / p.xa - 1.0 / xb;
    return p;
  }
  p.span = p.D > 0.0 ? subtended_angle(p.xa, xb, p.D) : 0.0;
  // The pdf peaks at 1 / (span D) at the foot point; the foot lies outside only when D is
  // well above the collinear threshold, so only the inside case can overflow.
  if (p.D <= 0.0 || !std::isfinite(float(1.0 / (p.span * p.D)))) {
    p.regime = Regime::kUniform;
    p.span = p.b - p.a;
  }
  return p;
}

double offset_for(const Prepared& p, double u) {
  switch (p.regime) {
    case Regime::kCauchy:
      return p.D * std::tan(std::atan(p.xa / p.D) + u * p.span);
    case Regime::kInverseSquare:
      return 1.0 / (1.0 / p.xa - u * p.span);
    case Regime::kUniform:
      break;
  }
  return p.xa + u * p.span;
}

double cdf_at_offset(const Prepared& p, double x) {
  switch (p.regime) {
    case Regime::kCauchy:
      return subtended_angle(p.xa, x, p.D) / p.span;
    case Regime::kInverseSquare:
      return (1.0 / p.xa - 1.0 / x) / p.span;
    case Regime::kUniform:
      break;
  }
  return (x - p.xa) / p.span;
}

double pdf_at_offset(const Prepared& p, double x) {
  switch (p.regime) {
    case Regime::kCauchy:
      return p.D / (p.span * (p.D * p.D + x * x));
    case Regime::kInverseSquare:
      return 1.0 / (p.span * x * x);
    case Regime::kUniform:
      break;
  }
  return 1.0 / p.span;
}

}  // namespace

// The perpendicular offset is taken from light - origin directly rather than by forming the
// foot point origin + dir * delta and subtracting it from light: one rounding fewer where the
// coordinates are large next to D.
EquiangularSetup make_equiangular_setup(Vec3 origin, Vec3 unit_dir, Vec3 light, float a, float b) {
  const Vec3 to_light = light - origin;
  const float delta = dot(to_light, unit_dir);
  return {a, b, delta, length(to_light - unit_dir * delta)};
}

float sample_equiangular(const EquiangularSetup& s, float u) {
  const Prepared p = prepare(s);
  return float(std::clamp(p.delta + offset_for(p, u), p.a, p.b));
}

float equiangular_pdf(const EquiangularSetup& s, float t) {
  if (!(t >= s.a && t <= s.b)) return 0.0f;
  const Prepared p = prepare(s);
  return float(pdf_at_offset(p, double(t) - p.delta));
}

float invert_equiangular(const EquiangularSetup& s, float t) {
  const Prepared p = prepare(s);
  const double x = std::clamp(double(t), p.a, p.b) - p.delta;
  return float(std::clamp(cdf_at_offset(p, x), 0.0, 1.0));
}

}  // namespace caligo
