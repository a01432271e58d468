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

enum Regime { kCauchy, kInverseSquare, kUniform };

// atan(x1 / D) - atan(x0 / D) for x0 <= x1, without the cancellation of subtracting two
// angles near +-pi/2: tan(A - B) = D (x1 - x0) / (D^2 + x0 x1), and atan2 keeps the branch
// when the difference exceeds pi/2. For x1 = +inf it is pi/2 - atan(x0 / D) = atan2(D, x0).
double subtended_angle(double x0, double x1, double D) {
  if (std::isinf(x1)) return std::atan2(D, x0);
  return std::atan2(D * (x1 - x0), D * D + x0 * x1);
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

EquiangularDistribution::EquiangularDistribution(const EquiangularSetup& s)
    : regime_(kCauchy), a_(s.a), b_(s.b), delta_(s.delta), D_(s.D), xa_(double(s.a) - s.delta), span_(0.0),
      theta_a_(0.0) {
  const double xb = b_ - delta_;
  const bool foot_outside = xa_ > 0.0 || xb < 0.0;
  if (foot_outside && D_ <= kCollinearRatio * std::min(std::abs(xa_), std::abs(xb))) {
    regime_ = kInverseSquare;
    span_ = 1.0 / xa_ - 1.0 / xb;
    return;
  }
  span_ = D_ > 0.0 ? subtended_angle(xa_, xb, D_) : 0.0;
  // The pdf peaks at 1 / (span D) at the foot point; the foot lies outside only when D is
  // well above the collinear threshold, so only the inside case can overflow.
  if (D_ <= 0.0 || !std::isfinite(float(1.0 / (span_ * D_)))) {
    regime_ = kUniform;
    span_ = b_ - a_;
    return;
  }
  theta_a_ = std::atan(xa_ / D_);
}

float EquiangularDistribution::sample(float u) const {
  double x = xa_ + u * span_;
  if (regime_ == kCauchy) x = D_ * std::tan(theta_a_ + u * span_);
  if (regime_ == kInverseSquare) x = 1.0 / (1.0 / xa_ - u * span_);
  return float(std::clamp(delta_ + x, a_, b_));
}

float EquiangularDistribution::pdf(float t) const {
  if (!(t >= a_ && t <= b_)) return 0.0f;
  const double x = double(t) - delta_;
  if (regime_ == kCauchy) return float(D_ / (span_ * (D_ * D_ + x * x)));
  if (regime_ == kInverseSquare) return float(1.0 / (span_ * x * x));
  return float(1.0 / span_);
}

float EquiangularDistribution::invert(float t) const {
  const double x = std::clamp(double(t), a_, b_) - delta_;
  double cdf = (x - xa_) / span_;
  if (regime_ == kCauchy) cdf = subtended_angle(xa_, x, D_) / span_;
  if (regime_ == kInverseSquare) cdf = (1.0 / xa_ - 1.0 / x) / span_;
  return float(std::clamp(cdf, 0.0, 1.0));
}

}  // namespace caligo
