// Phase functions (phase.h): evaluation, exact inverse-CDF sampling and mean cosines.
//
// Every sampler inverts the CDF of cos_theta = mu in closed form and then picks the azimuth
// uniformly in a frame around wo. The inverses below are our own derivations. Rather than
// return mu itself, each returns the pair (1 - mu, 1 + mu) as products of non-negative
// factors, so neither suffers cancellation near the poles, where peaked lobes put most of
// their samples; mu and sin^2(theta) = (1 - mu)(1 + mu) then follow to full precision. The
// same factorisation removes the division by g (or k) of the textbook inverse, so small g
// needs no isotropic special case and the sampled density stays exactly phase_eval.
//
// Preconditions: wo and wi are unit vectors; g and k lie in (-1, 1) (the scene loader
// validates them; a lobe with |g| = 1 is a delta distribution, which this set cannot hold).
// All functions are pure and thread-safe.
#include "media/phase.h"

#include <algorithm>
#include <cmath>
#include <variant>

#include "core/math.h"

namespace caligo {
namespace {

// cos_theta about the travel direction, carried as its two complements.
struct CosineComplements {
  float one_minus;  // 1 - mu, in [0, 2]
  float one_plus;   // 1 + mu, in [0, 2]
};

// Uniform mu in [-1, 1]: the CDF is (1 + mu) / 2.
CosineComplements sample_isotropic_cosine(float u) { return {2.0f * (1.0f - u), 2.0f * u}; }

// Henyey-Greenstein. The CDF of mu is F(mu) = (1 - g^2) / (2g) [(1 + g^2 - 2g mu)^(-1/2) - 1/(1 + g)].
// Solving F = u and factoring (1 -+ g)^2 - (1 + g^2 - 2g mu) as differences of squares gives, with
// d = (1 - u)(1 - g) + u(1 + g):
//   1 - mu = 2 (1 - g)^2 (1 - u) ((1 - u) + u (1 + g)) / d^2
//   1 + mu = 2 (1 + g)^2 u (u + (1 - u)(1 - g)) / d^2
// Every factor is a sum of non-negative terms for |g| < 1, u in [0, 1].
CosineComplements sample_hg_cosine(float u, float g) {
  const float v = 1.0f - u, gm = 1.0f - g, gp = 1.0f + g;
  const float inv_d2 = 1.0f / sqr(v * gm + u * gp);
  return {2.0f * sqr(gm) * v * (v + u * gp) * inv_d2, 2.0f * sqr(gp) * u * (u + v * gm) * inv_d2};
}

// Schlick. Over mu the density is (1 - k^2) / (2 (1 - k mu)^2), so
// F(mu) = (1 - k^2) / (2k) [1 / (1 - k mu) - 1 / (1 + k)]. Solving F = u gives
// mu = (2u - 1 + k) / d with d = (1 - u)(1 - k) + u(1 + k), whose complements factor as
//   1 - mu = 2 (1 - k)(1 - u) / d,   1 + mu = 2 (1 + k) u / d.
CosineComplements sample_schlick_cosine(float u, float k) {
  const float v = 1.0f - u, km = 1.0f - k, kp = 1.0f + k;
  const float inv_d = 1.0f / (v * km + u * kp);
  return {2.0f * km * v * inv_d, 2.0f * kp * u * inv_d};
}

// The direction at the sampled polar angle about wo, azimuth 2 pi u_phi.
Vec3 direction_about(Vec3 wo, CosineComplements c, float u_phi) {
  const float cos_theta =
      std::clamp(c.one_minus <= c.one_plus ? 1.0f - c.one_minus : c.one_plus - 1.0f, -1.0f, 1.0f);
  const float sin_theta = safe_sqrt(c.one_minus * c.one_plus);
  return Frame::from_z(wo).to_world(spherical_direction(sin_theta, cos_theta, 2.0f * kPi * u_phi));
}

// Maps u from [lo, hi) back onto [0, 1), keeping it uniform after a discrete choice.
float remap(float u, float lo, float hi) { return std::min((u - lo) / (hi - lo), kOneMinusEpsilon); }

struct Eval {
  float cos_theta;
  float operator()(const IsotropicPhase&) const { return kInv4Pi; }
  float operator()(const HenyeyGreensteinPhase& p) const { return henyey_greenstein(cos_theta, p.g); }
  float operator()(const SchlickPhase& p) const { return schlick(cos_theta, p.k); }
  float operator()(const DoubleHenyeyGreensteinPhase& p) const {
    return p.w * henyey_greenstein(cos_theta, p.g1) + (1.0f - p.w) * henyey_greenstein(cos_theta, p.g2);
  }
};

struct SampleDirection {
  Vec3 wo;
  Vec2 u;
  Vec3 operator()(const IsotropicPhase&) const {
    return direction_about(wo, sample_isotropic_cosine(u.x), u.y);
  }
  Vec3 operator()(const HenyeyGreensteinPhase& p) const {
    return direction_about(wo, sample_hg_cosine(u.x, p.g), u.y);
  }
  Vec3 operator()(const SchlickPhase& p) const {
    return direction_about(wo, sample_schlick_cosine(u.x, p.k), u.y);
  }
  // Picks a lobe with probability w and reuses u.x within it; the pdf is the mixture's.
  Vec3 operator()(const DoubleHenyeyGreensteinPhase& p) const {
    const bool first = u.x < p.w;
    const float u_lobe = first ? remap(u.x, 0.0f, p.w) : remap(u.x, p.w, 1.0f);
    return direction_about(wo, sample_hg_cosine(u_lobe, first ? p.g1 : p.g2), u.y);
  }
};

// Mean cosine of Schlick's function, analytically: E[mu] = (1 - k^2)/2 * integral over [-1, 1] of
// mu / (1 - k mu)^2; substituting s = 1 - k mu turns the integrand into (1 - s) / (k^2 s^2), whence
//   E[mu] = 1/k - (1 - k^2) atanh(k) / k^2.
// The two terms cancel as k -> 0, where the series sum over n >= 1 of 2 k^(2n-1) / (4n^2 - 1)
// = 2k/3 + 2k^3/15 + 2k^5/35 + ... is used instead.
double schlick_mean_cosine(double k) {
  if (std::abs(k) < 1e-2) {
    double sum = 0.0, power = k;
    for (int n = 1; n <= 4; ++n, power *= k * k) sum += 2.0 * power / (4.0 * n * n - 1.0);
    return sum;
  }
  return 1.0 / k - (1.0 - k * k) * std::atanh(k) / (k * k);
}

struct MeanCosine {
  float operator()(const IsotropicPhase&) const { return 0.0f; }
  float operator()(const HenyeyGreensteinPhase& p) const { return p.g; }
  float operator()(const SchlickPhase& p) const { return float(schlick_mean_cosine(p.k)); }
  float operator()(const DoubleHenyeyGreensteinPhase& p) const { return p.w * p.g1 + (1.0f - p.w) * p.g2; }
};

}  // namespace

// 1 + g^2 - 2 g mu is rewritten as (1 - g)^2 + 2g (1 - mu) for g >= 0 and (1 + g)^2 - 2g (1 + mu)
// otherwise: sums of non-negative terms, accurate in the peak of a strongly forward or backward lobe.
float henyey_greenstein(float cos_theta, float g) {
  const float denom = g >= 0.0f ? sqr(1.0f - g) + 2.0f * g * (1.0f - cos_theta)
                                : sqr(1.0f + g) - 2.0f * g * (1.0f + cos_theta);
  return kInv4Pi * (1.0f - g) * (1.0f + g) / (denom * std::sqrt(denom));
}

// 1 - k mu rewritten as above: (1 - k) + k (1 - mu) for k >= 0, (1 + k) - k (1 + mu) otherwise.
float schlick(float cos_theta, float k) {
  const float denom = k >= 0.0f ? (1.0f - k) + k * (1.0f - cos_theta) : (1.0f + k) - k * (1.0f + cos_theta);
  return kInv4Pi * (1.0f - k) * (1.0f + k) / sqr(denom);
}

float phase_eval(const PhaseFunction& phase, Vec3 wo, Vec3 wi) {
  return std::visit(Eval{std::clamp(dot(wo, wi), -1.0f, 1.0f)}, phase);
}

float phase_pdf(const PhaseFunction& phase, Vec3 wo, Vec3 wi) { return phase_eval(phase, wo, wi); }

// The pdf is evaluated at the returned direction, so it equals phase_eval bit for bit.
PhaseSample phase_sample(const PhaseFunction& phase, Vec3 wo, Vec2 u) {
  const Vec3 wi = std::visit(SampleDirection{wo, u}, phase);
  return {wi, phase_eval(phase, wo, wi)};
}

float phase_mean_cosine(const PhaseFunction& phase) { return std::visit(MeanCosine{}, phase); }

}  // namespace caligo
