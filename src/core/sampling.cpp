// Sampling triads; see sampling.h. Each inverse undoes its warp exactly (up to float rounding),
// which the round-trip tests in sampling_test.cpp check.
#include "core/sampling.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/math.h"

namespace caligo {
namespace {

float clamp_unit(float u) { return std::clamp(u, 0.0f, kOneMinusEpsilon); }

// Azimuth in [0, 2 pi) mapped to [0, 1).
float azimuth_to_unit(float x, float y) {
  float phi = std::atan2(y, x);
  if (phi < 0.0f) phi += 2.0f * kPi;
  return clamp_unit(phi * kInv2Pi);
}

}  // namespace

// ---- Disk ----------------------------------------------------------------------------------------

// Shirley & Chiu: the square [-1,1]^2 is split into four triangular wedges by its diagonals; each
// wedge's concentric squares map to concentric circles, which keeps strata compact.
Vec2 sample_uniform_disk_concentric(Vec2 u) {
  const float a = 2.0f * u.x - 1.0f, b = 2.0f * u.y - 1.0f;
  if (a == 0.0f && b == 0.0f) return {0.0f, 0.0f};
  float r, theta;
  if (std::abs(a) > std::abs(b)) {
    r = a;
    theta = (kPi / 4.0f) * (b / a);
  } else {
    r = b;
    theta = kPi / 2.0f - (kPi / 4.0f) * (a / b);
  }
  return {r * std::cos(theta), r * std::sin(theta)};
}

float uniform_disk_pdf() { return kInvPi; }

// In the left/right wedges p = a (cos t, sin t) with |t| < pi/4, so t = atan(y / x) and b = a t / (pi/4);
// the top/bottom wedges are the same with x and y swapped (pi/2 - t = atan(x / y)).
Vec2 invert_uniform_disk_concentric(Vec2 p) {
  if (p.x == 0.0f && p.y == 0.0f) return {0.5f, 0.5f};
  const float r = std::hypot(p.x, p.y);
  float a, b;
  if (std::abs(p.x) >= std::abs(p.y)) {
    a = std::copysign(r, p.x);
    b = a * std::atan(p.y / p.x) * (4.0f / kPi);
  } else {
    b = std::copysign(r, p.y);
    a = b * std::atan(p.x / p.y) * (4.0f / kPi);
  }
  return {clamp_unit(0.5f * (a + 1.0f)), clamp_unit(0.5f * (b + 1.0f))};
}

// ---- Sphere and hemisphere ----------------------------------------------------------------------

// z = 1 - 2 u.x; sin^2 = (1 - z)(1 + z) = 4 u.x (1 - u.x) stays accurate near the poles.
Vec3 sample_uniform_sphere(Vec2 u) {
  const float z = 1.0f - 2.0f * u.x;
  const float sin_theta = 2.0f * safe_sqrt(u.x * (1.0f - u.x));
  const float phi = 2.0f * kPi * u.y;
  return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), z};
}

float uniform_sphere_pdf() { return kInv4Pi; }

Vec2 invert_uniform_sphere(Vec3 w) { return {clamp_unit(0.5f * (1.0f - w.z)), azimuth_to_unit(w.x, w.y)}; }

Vec3 sample_uniform_hemisphere(Vec2 u) {
  const float z = u.x;
  const float sin_theta = safe_sqrt((1.0f - z) * (1.0f + z));
  const float phi = 2.0f * kPi * u.y;
  return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), z};
}

float uniform_hemisphere_pdf() { return kInv2Pi; }

Vec2 invert_uniform_hemisphere(Vec3 w) { return {clamp_unit(w.z), azimuth_to_unit(w.x, w.y)}; }

// Malley: uniform on the disk, projected up onto the hemisphere.
Vec3 sample_cosine_hemisphere(Vec2 u) {
  const Vec2 d = sample_uniform_disk_concentric(u);
  return {d.x, d.y, safe_sqrt(1.0f - d.x * d.x - d.y * d.y)};
}

// Zero below the horizon rather than negative, so a caller can never get a negative density.
float cosine_hemisphere_pdf(float cos_theta) { return std::max(cos_theta, 0.0f) * kInvPi; }

Vec2 invert_cosine_hemisphere(Vec3 w) { return invert_uniform_disk_concentric({w.x, w.y}); }

// ---- Cone ----------------------------------------------------------------------------------------

// 1 - cos(theta) is linear in u.x; working with it (instead of cos(theta)) keeps narrow cones
// accurate: sin^2 = (1 - cos)(1 + cos) = omc (2 - omc).
Vec3 sample_uniform_cone(Vec2 u, float cos_theta_max) {
  const float omc = u.x * (1.0f - cos_theta_max);
  const float sin_theta = safe_sqrt(omc * (2.0f - omc));
  const float phi = 2.0f * kPi * u.y;
  return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), 1.0f - omc};
}

// Infinite for a degenerate cone (cos_theta_max == 1): it is a delta direction.
float uniform_cone_pdf(float cos_theta_max) { return 1.0f / (2.0f * kPi * (1.0f - cos_theta_max)); }

// 1 - cos(theta) = sin^2 / (1 + cos), from the x and y components, which hold the precision for
// directions near the axis. A degenerate cone has only one direction; any u.x produces it.
Vec2 invert_uniform_cone(Vec3 w, float cos_theta_max) {
  const float width = 1.0f - cos_theta_max;
  if (!(width > 0.0f)) return {0.0f, azimuth_to_unit(w.x, w.y)};
  const float omc = (w.x * w.x + w.y * w.y) / (1.0f + w.z);
  return {clamp_unit(omc / width), azimuth_to_unit(w.x, w.y)};
}

// ---- Triangle ------------------------------------------------------------------------------------

// Heitz 2019, "A Low-Distortion Map Between Triangle and Square": the square's two halves (split by
// its diagonal) are sheared onto the triangle, area-preserving (Jacobian 1/2) and with a clean
// piecewise-linear inverse, unlike the sqrt warp. Barycentrics are (b0, b1, 1 - b0 - b1).
Vec3 sample_uniform_triangle(Vec2 u) {
  float b0, b1;
  if (u.x < u.y) {
    b0 = 0.5f * u.x;
    b1 = u.y - b0;
  } else {
    b1 = 0.5f * u.y;
    b0 = u.x - b1;
  }
  return {b0, b1, 1.0f - b0 - b1};
}

// The branch is decided by b0 < b1, which is equivalent to u.x < u.y in the forward map.
Vec2 invert_uniform_triangle(Vec3 b) {
  if (b.x < b.y) return {clamp_unit(2.0f * b.x), clamp_unit(b.y + b.x)};
  return {clamp_unit(b.x + b.y), clamp_unit(2.0f * b.y)};
}

// ---- Discrete distribution -----------------------------------------------------------------------

// Rejects what would make the distribution meaningless: a negative or non-finite weight, or no
// positive weight at all (an empty span included).
DiscreteDistribution::DiscreteDistribution(std::span<const float> weights) {
  double total = 0.0;
  for (size_t i = 0; i < weights.size(); ++i) {
    if (!std::isfinite(weights[i]) || weights[i] < 0.0f)
      throw std::invalid_argument("DiscreteDistribution: weight " + std::to_string(i) + " is " +
                                  std::to_string(weights[i]) + "; weights must be finite and >= 0");
    total += weights[i];
  }
  if (!(total > 0.0) || !std::isfinite(float(total)))
    throw std::invalid_argument("DiscreteDistribution: weights must have a positive, finite sum");
  pmf_.resize(weights.size());
  cdf_.resize(weights.size() + 1);
  double running = 0.0;  // accumulated in double so long lists keep an accurate cdf
  for (size_t i = 0; i < weights.size(); ++i) {
    pmf_[i] = float(weights[i] / total);
    cdf_[i] = float(running / total);
    running += weights[i];
  }
  cdf_.back() = 1.0f;
  total_ = float(total);
}

// Bucket i covers [cdf_[i], cdf_[i+1]); the last cdf entry <= u names a non-empty bucket, so
// zero-weight entries are never chosen.
int DiscreteDistribution::sample(float u, float* pmf_out, float* u_remapped) const {
  u = u >= 0.0f ? std::min(u, kOneMinusEpsilon) : 0.0f;  // also maps NaN to 0
  const auto it = std::upper_bound(cdf_.begin(), cdf_.end(), u);
  const size_t i = size_t(it - cdf_.begin()) - 1;
  if (pmf_out) *pmf_out = pmf_[i];
  if (u_remapped) *u_remapped = clamp_unit((u - cdf_[i]) / (cdf_[i + 1] - cdf_[i]));
  return int(i);
}

// ---- Multiple importance sampling ----------------------------------------------------------------

// Written as 1 / (1 + (g/f)^2) so that large finite pdfs do not overflow when squared.
float power_heuristic(int nf, float f_pdf, int ng, float g_pdf) {
  const float f = float(nf) * f_pdf, g = float(ng) * g_pdf;
  if (std::isinf(f)) return 1.0f;
  if (f == 0.0f) return 0.0f;
  const float r = g / f;
  return 1.0f / (1.0f + r * r);
}

float balance_heuristic(int nf, float f_pdf, int ng, float g_pdf) {
  const float f = float(nf) * f_pdf, g = float(ng) * g_pdf;
  if (std::isinf(f)) return 1.0f;
  if (f == 0.0f) return 0.0f;
  return 1.0f / (1.0f + g / f);
}

}  // namespace caligo
