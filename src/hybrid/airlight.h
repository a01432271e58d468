// The analytic airlight of Sun, Ramamoorthi, Narasimhan and Nayar (2005, "A Practical Analytic
// Single Scattering Model for Real Time Rendering"), as the hybrid of Wyman and Ramsey (2008)
// uses it: single scattering of an isotropic point light of intensity I0 (W/sr) in an
// unbounded homogeneous medium, isotropic phase 1/(4π), scattering σ_s and extinction σ_t
// (Sun et al. take σ_s = σ_t = β; we keep them apart: σ_t attenuates both legs, σ_s scales the
// in-scattering once). A view ray from the eye with unit direction ω sees the light at distance
// D and angle γ; h = D sin γ is the ray's closest approach to the light, reached at t = D cos γ.
//
//   L(t0, t1) = σ_s I0 / (4π) ∫_{t0}^{t1} e^{-σ_t (t + d(t))} / d(t)² dt,   d(t)² = h² + (t - D cos γ)²
//
// With t - D cos γ = h tan θ and ξ = π/4 + θ/2 this is Sun et al.'s closed form
//
//   L(t0, t1) = A0 [F(A1, ξ(t1)) - F(A1, ξ(t0))],      F(u, v) = ∫_0^v e^{-u tan ξ} dξ,
//   A0 = σ_s I0 e^{-σ_t D cos γ} / (2π D sin γ),  A1 = σ_t D sin γ,
//   ξ(t) = π/4 + ½ atan((t - D cos γ) / (D sin γ)),  ξ(0) = γ/2,  ξ(∞) = π/2.
//
// (The exponent in A0 is D cos γ, not D: the test against the integral decides it.) Taken
// literally the difference of two F lookups times A0 is unusable when the light is behind the
// viewer: A0 grows like e^{σ_t D} while the difference shrinks like e^{-σ_t D (1 - cos γ)}, so
// float rounding in F is amplified by up to e^{2 σ_t D}. We therefore tabulate the scaled tail
//
//   H(u, v) = ∫_v^{π/2} e^{-u (tan ξ - tan v)} dξ = e^{u tan v} [F(u, π/2) - F(u, v)]   (0 <= H <= π/2 - v)
//
// and evaluate the same closed form as L(t0, t1) = T(t0) - T(t1) with the tail
//
//   T(t) = A0 e^{-A1 tan ξ(t)} H(A1, ξ(t)) = σ_s I0 e^{-σ_t (t + d(t))} H(A1, ξ(t)) / (2π h),
//
// every factor bounded (A1 tan ξ(t) + σ_t D cos γ = σ_t (t + d(t)), the true optical path).
// F itself is F(u, v) = H(u, 0) - e^{-u tan v} H(u, v). Errors and timings: airlight_test.cpp
// and docs/techniques.md.
//
// Degenerate geometry: a ray through a point light has infinite airlight (∫ dt/d² diverges), so
// the light is held at least `min_distance` from the eye and from every ray (h and D are clamped
// to it); this is the exact airlight of a light displaced by at most min_distance. σ_t = 0 gives
// L = σ_s I0 (ξ1 - ξ0) / (2π h); T = ∞ is the limit ξ = π/2, T(∞) = 0. No NaN, never negative.
//
// Thread safety: tables are immutable after construction; lookups may run concurrently.
#pragma once

#include <vector>

#include "core/vec.h"

namespace caligo {

// Direct adaptive quadrature in double (absolute tolerance ~1e-12): the reference the tables
// are built from and tested against. u >= 0, v in [0, π/2].
double airlight_F_quadrature(double u, double v);
double airlight_H_quadrature(double u, double v);

// E(u, v) = (1 + u) H(u, v) on a grid: a = (u / (1 + u))^(1/4) uniform in [0, 1] (u = 0 .. ∞;
// the root resolves H's u·ln u behaviour at u = 0, the last row is the exact limit
// (1 + u) H -> cos² v), and q = 1 - (x / (π/2))^(1/4) uniform in [0, 1] for the complement
// x = π/2 - v. Near u = 0, x = 0 H is close to homogeneous of degree one (H ≈ x φ(u / x)), so
// the error there follows the *relative* spacing, which fourth-root grids keep small. Lookups take the
// complement x, which callers get without cancellation (π/2 - ξ(t) = ½ atan2(h, t - D cos γ)). Inputs outside
// are clamped.
class AirlightTable {
 public:
  struct Options {
    int u_samples = 256;
    int v_samples = 512;
  };
  // One u (one A1: constant per pixel), so a lookup per ray endpoint is a lerp of two rows.
  struct Row {
    const float* lo = nullptr;
    const float* hi = nullptr;
    float weight = 0.0f;          // of hi
    float inv_one_plus_u = 1.0f;  // undoes the (1 + u) scaling
  };

  AirlightTable() : AirlightTable(Options{}) {}
  explicit AirlightTable(Options options);
  // The default table, built once on first use (~0.1 s).
  static const AirlightTable& shared();

  Row row(float u) const;
  // H at v = π/2 - x.
  float H_complement(const Row& r, float x) const;
  float H(float u, float v) const;
  float F(float u, float v) const;
  int u_samples() const { return nu_; }
  int v_samples() const { return nv_; }

 private:
  int nu_ = 0, nv_ = 0;
  std::vector<float> e_;  // E, row-major: nu rows of nv columns in q
};

struct AirlightMedium {
  float sigma_s = 0.0f;
  float sigma_t = 0.0f;
};

// Sun et al.'s per-pixel constants for one view ray and one point light, after the clamps above.
struct AirlightRay {
  float scale = 0.0f;  // σ_s I0 / (2π h) = A0 e^{σ_t D cos γ}
  float a1 = 0.0f;     // A1 = σ_t h
  float sigma_t = 0.0f;
  float along = 0.0f;  // D cos γ: ray parameter of the closest approach
  float h = 0.0f;      // D sin γ, >= min_distance
  AirlightTable::Row row;
};

inline constexpr float kAirlightMinDistance = 1e-3f;

AirlightRay make_airlight_ray(const AirlightTable& table, const AirlightMedium& medium, float intensity,
                              float light_distance, float cos_gamma,
                              float min_distance = kAirlightMinDistance);
// The same from positions: `dir` must be unit length.
AirlightRay make_airlight_ray(const AirlightTable& table, const AirlightMedium& medium, float intensity,
                              Vec3 light, Vec3 eye, Vec3 dir, float min_distance = kAirlightMinDistance);

// T(t): the airlight of the ray from t to infinity (t < 0 reads as 0; t = ∞ gives 0).
float airlight_tail(const AirlightTable& table, const AirlightRay& ray, float t);
// L(t0, t1) = T(t0) - T(t1), clamped at 0; empty when t1 <= t0.
float airlight_interval(const AirlightTable& table, const AirlightRay& ray, float t0, float t1);
// The whole ray from the eye to t_max (a surface, or kInfinity).
inline float airlight(const AirlightTable& table, const AirlightRay& ray, float t_max) {
  return airlight_interval(table, ray, 0.0f, t_max);
}

// Wyman and Ramsey's per-frame refactoring F_C(cos γ, x): with the eye, the light and the medium
// fixed for a frame, A0 and A1 depend on γ alone, so one table indexed by γ and a position along
// the ray gives each march step as one lookup, one subtraction and one multiply. We tabulate
//
//   P(γ, w) = ∫_{γ/2}^{ξ} e^{σ_t D - σ_t D cos γ - A1 tan ξ'} dξ',  ξ = γ/2 + w (π/2 - γ/2),  w in [0, 1]
//
// (the cumulative airlight from the eye, scaled by e^{σ_t D} so it stays in [0, π/2]: the
// paper's F_C minus its value at the eye), rows uniform in r with γ = π (3r² - 2r³), columns uniform in
// q = 1 - (1 - w)^(1/4) (the integrand's drop near ξ = π/2 in thin media is steep), so a lit
// interval is L(t0, t1) = S (P(γ, w(t1)) - P(γ, w(t0))) with S = σ_s I0 e^{-σ_t D} / (2π h)
// per pixel. Built from the AirlightTable in ~1 ms per light per frame. Error against the closed
// form, relative to the pixel's whole-ray airlight: <= 0.3% for σ_t D <= 1, 0.6% at 5, 4% at 20,
// 15% at 50 (the in-scattering then hugs the eye, w ≈ 0): past σ_t D ≈ 5 use airlight_tail.
// The scattering passes use it with HybridSettings::frame_table (off by default: slower than
// airlight_tail on a CPU, docs/techniques.md).
class FrameAirlight {
 public:
  struct Options {
    int gamma_samples = 128;
    int w_samples = 256;
    float min_distance = kAirlightMinDistance;
  };
  struct Ray {
    const float* lo = nullptr;  // the two rows around γ
    const float* hi = nullptr;
    float weight = 0.0f;
    float along = 0.0f;      // D cos γ
    float h = 0.0f;          // D sin γ (clamped)
    float inv_range = 0.0f;  // 1 / (π/2 - γ/2): 1 - w = (π/2 - ξ) / (π/2 - γ/2)
    float scale = 0.0f;      // S
  };

  FrameAirlight(const AirlightTable& table, const AirlightMedium& medium, float intensity, Vec3 light,
                Vec3 eye, Options options);
  FrameAirlight(const AirlightTable& table, const AirlightMedium& medium, float intensity, Vec3 light,
                Vec3 eye)
      : FrameAirlight(table, medium, intensity, light, eye, Options{}) {}

  // Per pixel: `dir` unit length.
  Ray ray(Vec3 dir) const;
  Ray ray_cos(float cos_gamma) const;
  // P(γ, w(t)) (unitless; multiply differences by ray.scale).
  float cumulative(const Ray& ray, float t) const;
  float interval(const Ray& ray, float t0, float t1) const;
  float light_distance() const { return distance_; }

 private:
  Vec3 light_, eye_;
  float distance_ = 0.0f;  // D, >= min_distance
  float min_distance_ = 0.0f;
  float scale_ = 0.0f;  // σ_s I0 e^{-σ_t D} / (2π)
  int ng_ = 0, nw_ = 0;
  std::vector<float> p_;  // P, row-major: ng rows of nw
};

}  // namespace caligo
