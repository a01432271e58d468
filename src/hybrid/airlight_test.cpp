#include "hybrid/airlight.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "core/rng.h"

namespace caligo {
namespace {

constexpr double kPiD = std::numbers::pi;

// Adaptive Simpson written again here so the reference shares nothing with the code under test.
template <class Fn>
double simpson(const Fn& f, double a, double b, double fa, double fm, double fb, double whole, double eps,
               int depth) {
  const double m = 0.5 * (a + b), flm = f(0.5 * (a + m)), frm = f(0.5 * (m + b));
  const double left = (m - a) / 6 * (fa + 4 * flm + fm), right = (b - m) / 6 * (fm + 4 * frm + fb);
  if (depth > 40 || (depth > 4 && std::abs(left + right - whole) <= 15 * eps)) return left + right;
  const double e = depth < 20 ? eps / 2 : eps;  // a floor, so rounding noise cannot recurse to every leaf
  return simpson(f, a, m, fa, flm, fm, left, e, depth + 1) +
         simpson(f, m, b, fm, frm, fb, right, e, depth + 1);
}
template <class Fn>
double integrate(const Fn& f, double a, double b, double eps) {
  if (!(b > a)) return 0.0;
  const double fa = f(a), fm = f(0.5 * (a + b)), fb = f(b);
  return simpson(f, a, b, fa, fm, fb, (b - a) / 6 * (fa + 4 * fm + fb), eps, 0);
}

struct Geometry {
  double distance;   // D, eye to light
  double cos_gamma;  // between the view ray and the direction to the light
};

// The single-scattering integral itself, σ_s I0/(4π) ∫ e^{-σ_t (t + d)} / d² dt with
// d² = D² + t² - 2 t D cos γ (law of cosines, no angle substitution), split at the closest
// approach and around it, the infinite tail mapped to [0, 1).
double reference_airlight(Geometry g, double sigma_s, double sigma_t, double intensity, double t0,
                          double t1) {
  const double c = g.cos_gamma, dist = g.distance;
  const double h = dist * std::sqrt(std::max(0.0, 1 - c * c)), tc = dist * c;
  auto integrand = [&](double t) {
    const double d2 = std::max(dist * dist + t * t - 2 * t * dist * c, 1e-300);
    return std::exp(-sigma_t * (t + std::sqrt(d2))) / d2;
  };
  const double scale = kPiD / h * std::exp(-sigma_t * dist);  // bounds the whole integral
  const double eps = 1e-10 * scale;
  std::vector<double> cuts = {t0};
  for (double k : {-100.0, -10.0, -1.0, 0.0, 1.0, 10.0, 100.0})
    if (tc + k * h > t0 && tc + k * h < t1) cuts.push_back(tc + k * h);
  double last = std::isinf(t1) ? std::max(t0, tc + 100 * h) : t1;
  if (std::isinf(t1) && last > t0 && cuts.back() < last) cuts.push_back(last);
  if (!std::isinf(t1)) cuts.push_back(t1);
  double sum = 0;
  for (size_t i = 0; i + 1 < cuts.size(); ++i) sum += integrate(integrand, cuts[i], cuts[i + 1], eps);
  if (std::isinf(t1)) {
    auto tail = [&](double s) {
      if (s >= 1.0) return sigma_t > 0 ? 0.0 : 1.0;
      const double t = last + s / (1 - s);
      return integrand(t) / ((1 - s) * (1 - s));
    };
    sum += integrate(tail, 0.0, 1.0, eps);
  }
  return sigma_s * intensity / (4 * kPiD) * sum;
}

double log_uniform(Pcg32& rng, double lo, double hi) {
  return std::pow(10.0, std::log10(lo) + (std::log10(hi) - std::log10(lo)) * rng.next_float());
}

// ---------------------------------------------------------------------------------------------
// The tables against direct quadrature.

TEST(AirlightTable, FAndHMatchQuadrature) {
  const AirlightTable& table = AirlightTable::shared();
  Pcg32 rng(7, 1);
  double max_f = 0, max_h = 0, max_h_rel = 0;
  for (int i = 0; i < 4000; ++i) {
    const double u = i % 10 == 0 ? 0.0 : log_uniform(rng, 1e-4, 200.0);
    const double v = rng.next_float() * kPiD / 2;
    max_f = std::max(max_f, std::abs(table.F(float(u), float(v)) - airlight_F_quadrature(u, v)));
    const double h = airlight_H_quadrature(u, v);
    const double err = std::abs(table.H(float(u), float(v)) - h);
    max_h = std::max(max_h, err);
    max_h_rel = std::max(max_h_rel, (1 + u) * err);  // the error relative to H's scale cos² v / u
  }
  std::printf("airlight table 256x512: max |F - quad| %.2e, max |H - quad| %.2e, max (1+u)|H - quad| %.2e\n",
              max_f, max_h, max_h_rel);
  EXPECT_LT(max_f, 2e-4);
  EXPECT_LT(max_h, 2e-4);
  EXPECT_LT(max_h_rel, 5e-4);
}

TEST(AirlightTable, ExactRowsAndLimits) {
  const AirlightTable& table = AirlightTable::shared();
  for (float v : {0.0f, 0.3f, 1.0f, 1.5f}) {
    EXPECT_NEAR(table.F(0.0f, v), v, 2e-5f);  // u = 0: F = v (linear in v, not in the table's q)
    EXPECT_NEAR(table.H(0.0f, v), kPiD / 2 - v, 2e-5f);
    EXPECT_NEAR(table.H(1e20f, v), 0.0f, 1e-12f);  // u -> ∞: H ~ cos² v / u
    EXPECT_NEAR(table.H(1e6f, v) * 1e6f, std::pow(std::cos(v), 2.0f), 1e-3f);
  }
  EXPECT_EQ(table.F(5.0f, 0.0f), 0.0f);
  // F(u, π/2) = ∫_0^∞ e^{-u s} / (1 + s²) ds; at u = 1 it is Ci(1) sin 1 + (π/2 - Si(1)) cos 1.
  EXPECT_NEAR(table.F(1.0f, float(kPiD / 2)), 0.6214496242358134, 2e-5);
  EXPECT_NEAR(airlight_F_quadrature(1.0, kPiD / 2), 0.6214496242358134, 1e-9);
}

// ---------------------------------------------------------------------------------------------
// The closed form against the single-scattering integral.

TEST(Airlight, NormalisationAnalytic) {
  // σ_t = 0, γ = 90°, whole ray: σ_s I0/(4π) ∫_0^∞ dt / (h² + t²) = σ_s I0 / (8 h).
  const AirlightRay ray = make_airlight_ray(AirlightTable::shared(), {0.5f, 0.0f}, 3.0f, 2.0f, 0.0f);
  EXPECT_NEAR(airlight(AirlightTable::shared(), ray, kInfinity), 0.5 * 3.0 / (8 * 2.0), 1e-6);
  EXPECT_NEAR(reference_airlight({2.0, 0.0}, 0.5, 0.0, 3.0, 0.0, INFINITY), 0.5 * 3.0 / (8 * 2.0), 1e-9);
}

// Sun et al.'s A0 [F(A1, v) - F(A1, γ/2)] taken literally (with quadrature F), and the variant
// with e^{-β D} in A0 instead of e^{-β D cos γ}: the integral decides between them.
TEST(Airlight, LiteralSunFormDecidesA0) {
  Pcg32 rng(3, 5);
  for (int i = 0; i < 200; ++i) {
    const double dist = log_uniform(rng, 0.1, 10), gamma = 0.05 + 3.0 * rng.next_float();
    const double beta = log_uniform(rng, 0.01, 1), t = dist * log_uniform(rng, 0.1, 10);
    const double a1 = beta * dist * std::sin(gamma);
    const double v = kPiD / 4 + 0.5 * std::atan((t - dist * std::cos(gamma)) / (dist * std::sin(gamma)));
    const double diff = airlight_F_quadrature(a1, v) - airlight_F_quadrature(a1, gamma / 2);
    const double a0 = beta * std::exp(-beta * dist * std::cos(gamma)) / (2 * kPiD * dist * std::sin(gamma));
    const double a0_wrong = beta * std::exp(-beta * dist) / (2 * kPiD * dist * std::sin(gamma));
    const double ref = reference_airlight({dist, std::cos(gamma)}, beta, beta, 1.0, 0.0, t);
    EXPECT_NEAR(a0 * diff, ref, 1e-7 * ref + 1e-12) << dist << " " << gamma << " " << beta << " " << t;
    if (beta * dist * (1 - std::cos(gamma)) > 0.05) {
      EXPECT_GT(std::abs(a0_wrong * diff - ref), 0.01 * ref);
    }
  }
}

struct Sample {
  Geometry geometry;
  double sigma_s, sigma_t, intensity, t0, t1;
};

// Random geometry and media, a third of them near-degenerate (ray almost through the light or
// pointing away from it, light near the eye, optically thick, no extinction, infinite rays).
Sample random_sample(Pcg32& rng) {
  Sample s;
  s.geometry.distance = log_uniform(rng, 0.01, 100);
  const float kind = rng.next_float();
  const double gamma = kind < 0.15  ? log_uniform(rng, 1e-4, 0.05)
                       : kind < 0.3 ? kPiD - log_uniform(rng, 1e-4, 0.05)
                                    : kPiD * rng.next_float();
  s.geometry.cos_gamma = std::cos(gamma);
  s.sigma_t = rng.next_float() < 0.1 ? 0.0 : log_uniform(rng, 1e-3, 10);
  s.sigma_s = s.sigma_t > 0 ? s.sigma_t * rng.next_float() : log_uniform(rng, 1e-3, 1);
  s.intensity = log_uniform(rng, 0.1, 1000);
  s.t1 = rng.next_float() < 0.25 ? INFINITY : s.geometry.distance * log_uniform(rng, 0.01, 10);
  s.t0 =
      rng.next_float() < 0.5 ? 0.0 : (std::isinf(s.t1) ? 2 * s.geometry.distance : s.t1) * rng.next_float();
  return s;
}

// The geometry the clamped ray actually models (a light displaced by at most min_distance).
Geometry effective(const AirlightRay& ray) {
  const double d = std::hypot(double(ray.along), double(ray.h));
  return {d, ray.along / d};
}

// The natural scale of a pixel's airlight, σ_s I0 e^{-σ_t D} / (2π h): errors are judged
// relative to the value and to this (the rays that see the light at all see about this much).
double pixel_scale(const Sample& s, const AirlightRay& ray) {
  return s.sigma_s * s.intensity * std::exp(-s.sigma_t * s.geometry.distance) / (2 * kPiD * ray.h);
}

TEST(Airlight, ClosedFormMatchesSingleScatteringIntegral) {
  const AirlightTable& table = AirlightTable::shared();
  Pcg32 rng(11, 2);
  double worst_rel = 0, worst_scaled = 0;
  for (int i = 0; i < 3000; ++i) {
    const Sample s = random_sample(rng);
    const AirlightRay ray = make_airlight_ray(table, {float(s.sigma_s), float(s.sigma_t)}, float(s.intensity),
                                              float(s.geometry.distance), float(s.geometry.cos_gamma));
    const double got = airlight_interval(table, ray, float(s.t0), float(s.t1));
    const double ref = reference_airlight(effective(ray), s.sigma_s, s.sigma_t, s.intensity, s.t0, s.t1);
    const double err = std::abs(got - ref), scale = pixel_scale(s, ray);
    ASSERT_TRUE(std::isfinite(got) && got >= 0.0);
    if (scale > 1e-25) {  // else float underflow: the bound's 1e-30 floor covers these
      worst_scaled = std::max(worst_scaled, err / scale);
      if (ref > 1e-3 * scale) worst_rel = std::max(worst_rel, err / ref);
    }
    // (1e-30: float's exp underflows far before double's)
    EXPECT_LE(err, 2e-3 * ref + 2e-5 * scale + 1e-30)
        << "D " << s.geometry.distance << " cos " << s.geometry.cos_gamma << " sigma " << s.sigma_s << "/"
        << s.sigma_t << " t " << s.t0 << ".." << s.t1 << " got " << got << " ref " << ref;
  }
  std::printf("closed form vs integral: max rel err %.2e (where L > 1e-3 scale), max err / scale %.2e\n",
              worst_rel, worst_scaled);
}

TEST(Airlight, SubIntervalsAdd) {
  const AirlightTable& table = AirlightTable::shared();
  Pcg32 rng(5, 9);
  for (int i = 0; i < 2000; ++i) {
    const Sample s = random_sample(rng);
    const AirlightRay ray = make_airlight_ray(table, {float(s.sigma_s), float(s.sigma_t)}, float(s.intensity),
                                              float(s.geometry.distance), float(s.geometry.cos_gamma));
    const float a = float(s.t0), c = std::isinf(s.t1) ? kInfinity : float(s.t1) + 1.0f;
    const float b = a + (std::isinf(c) ? 3.0f : (c - a) * rng.next_float());
    const float whole = airlight_interval(table, ray, a, c);
    const float parts = airlight_interval(table, ray, a, b) + airlight_interval(table, ray, b, c);
    // Exact but for the clamp at zero, which can act where the table's error (< 5e-5 of the
    // scale) exceeds a thin interval's airlight.
    EXPECT_NEAR(parts, whole, 1e-5f * whole + 5e-5f * float(pixel_scale(s, ray)));
  }
}

TEST(Airlight, DegenerateLimits) {
  const AirlightTable& table = AirlightTable::shared();
  // Through the light (γ = 0): the light is held min_distance off the ray, so the airlight is
  // that of a ray passing at min_distance, finite and matching the integral for that geometry.
  for (float cos_gamma : {1.0f, -1.0f}) {
    const AirlightRay ray = make_airlight_ray(table, {0.2f, 0.3f}, 10.0f, 2.0f, cos_gamma);
    EXPECT_EQ(ray.h, kAirlightMinDistance);
    const double ref = reference_airlight(effective(ray), 0.2, 0.3, 10.0, 0.0, INFINITY);
    EXPECT_NEAR(airlight(table, ray, kInfinity), ref, 2e-3 * ref);
  }
  // Light at the eye: every ray starts at min_distance from it.
  const AirlightRay at_eye = make_airlight_ray(table, {0.2f, 0.3f}, 10.0f, 0.0f, 0.3f);
  EXPECT_TRUE(std::isfinite(airlight(table, at_eye, kInfinity)));
  EXPECT_GT(airlight(table, at_eye, kInfinity), 0.0f);
  // No extinction: σ_s I0 (ξ1 - ξ0) / (2π h), here γ = 60°, D = 1, whole ray: ξ from π/6 to π/2.
  const AirlightRay clear = make_airlight_ray(table, {1.0f, 0.0f}, 1.0f, 1.0f, 0.5f);
  EXPECT_NEAR(airlight(table, clear, kInfinity), (kPiD / 2 - kPiD / 6) / (2 * kPiD * std::sqrt(0.75)), 2e-5);
  // Empty media and empty intervals.
  EXPECT_EQ(airlight(table, make_airlight_ray(table, {0.0f, 0.0f}, 1.0f, 1.0f, 0.5f), kInfinity), 0.0f);
  EXPECT_EQ(airlight_interval(table, clear, 2.0f, 2.0f), 0.0f);
  EXPECT_EQ(airlight_interval(table, clear, 3.0f, 2.0f), 0.0f);
}

TEST(Airlight, NoNanOrNegativeOnExtremeInputs) {
  const AirlightTable& table = AirlightTable::shared();
  const float big = 1e30f, inf = kInfinity;
  int checked = 0;
  for (float dist : {0.0f, 1e-9f, 1e-3f, 1.0f, 1e3f, 1e7f})
    for (float c : {-1.0f, -0.9999999f, -0.5f, 0.0f, 0.9999999f, 1.0f, 1.5f})
      for (float sigma_t : {0.0f, 1e-8f, 1.0f, 1e4f})
        for (float sigma_s : {0.0f, 1.0f, 1e4f}) {
          const AirlightRay ray = make_airlight_ray(table, {sigma_s, sigma_t}, 1e3f, dist, c);
          for (float t0 : {-1.0f, 0.0f, 1e-6f, 1.0f, 1e6f})
            for (float t1 : {0.0f, 1e-6f, 1.0f, dist, 1e6f, big, inf}) {
              const float l = airlight_interval(table, ray, t0, t1);
              ASSERT_TRUE(std::isfinite(l) && l >= 0.0f)
                  << dist << " " << c << " " << sigma_t << " " << t0 << " " << t1;
              ++checked;
            }
        }
  EXPECT_GT(checked, 10000);
}

// ---------------------------------------------------------------------------------------------
// The per-frame table against the closed form.

TEST(FrameAirlight, MatchesClosedForm) {
  const AirlightTable& table = AirlightTable::shared();
  Pcg32 rng(21, 4);
  double worst = 0;
  for (int frame = 0; frame < 40; ++frame) {
    const Vec3 eye(rng.next_float() * 4 - 2, rng.next_float() * 4 - 2, rng.next_float() * 4 - 2);
    const Vec3 light = eye + Vec3(rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float() - 0.5f) *
                                 float(log_uniform(rng, 0.1, 40));
    const float sigma_t = frame % 8 == 0 ? 0.0f : float(log_uniform(rng, 1e-3, 0.5));
    const AirlightMedium medium{sigma_t > 0 ? sigma_t * 0.8f : 0.1f, sigma_t};
    const FrameAirlight frame_table(table, medium, 50.0f, light, eye);
    for (int i = 0; i < 200; ++i) {
      Vec3 dir(rng.next_float() * 2 - 1, rng.next_float() * 2 - 1, rng.next_float() * 2 - 1);
      if (i < 20)
        dir = light - eye +
              Vec3(rng.next_float(), rng.next_float(), rng.next_float()) * 0.05f;  // near the light
      dir = normalize(dir);
      const AirlightRay ray = make_airlight_ray(table, medium, 50.0f, light, eye, dir);
      const FrameAirlight::Ray fray = frame_table.ray(dir);
      const float t1 = float(log_uniform(rng, 0.01, 100)), t0 = t1 * rng.next_float() * (i % 2);
      const float got = frame_table.interval(fray, t0, t1);
      const float want = airlight_interval(table, ray, t0, t1);
      const float total =
          airlight(table, ray, kInfinity);  // the pixel's whole airlight: errors relative to it
      ASSERT_TRUE(std::isfinite(got) && got >= 0.0f);
      worst = std::max(worst, double(std::abs(got - want) / total));
      EXPECT_NEAR(got, want, 5e-3f * total) << "frame " << frame << " ray " << i << " t " << t0 << ".." << t1
                                            << " D " << frame_table.light_distance() << " sigma_t " << sigma_t
                                            << " h " << ray.h << " along " << ray.along;
    }
  }
  std::printf("frame table 128x256 vs closed form: max |err| / pixel total %.2e (sigma_t D <= 20)\n", worst);
}

TEST(FrameAirlight, SubIntervalsAddAndNoNan) {
  const AirlightTable& table = AirlightTable::shared();
  const Vec3 eye(0, 0, 0);
  for (Vec3 light : {Vec3(0, 0, 0), Vec3(0, 0, 1e-6f), Vec3(0, 0, 3), Vec3(0, 0, 1e4f)})
    for (float sigma_t : {0.0f, 0.1f, 100.0f}) {
      const FrameAirlight frame(table, {0.5f, sigma_t}, 10.0f, light, eye);
      for (Vec3 dir : {Vec3(0, 0, 1), Vec3(0, 0, -1), Vec3(1, 0, 0), normalize(Vec3(0, 1e-4f, 1))}) {
        const FrameAirlight::Ray r = frame.ray(dir);
        for (float t : {0.0f, 1e-6f, 1.0f, 2.999f, 3.0f, 1e6f, kInfinity}) {
          const float a = frame.interval(r, 0.0f, t), b = frame.interval(r, t, kInfinity);
          const float whole = frame.interval(r, 0.0f, kInfinity);
          ASSERT_TRUE(std::isfinite(a) && std::isfinite(b) && a >= 0 && b >= 0);
          EXPECT_NEAR(a + b, whole, 1e-5f * whole);
        }
      }
    }
}

}  // namespace
}  // namespace caligo
