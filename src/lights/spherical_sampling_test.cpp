// Solid-angle sampling of quad and triangle lights (Urena et al. 2013 spherical rectangles,
// Arvo 1995 spherical triangles, lights/area_light_sampling.h): chi-squared against the
// numerically integrated solid-angle density, the pdf integrates to one over the light,
// light_pdf equals the sampler's density, and the area-sampling thresholds on both sides.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "core/rng.h"
#include "core/sampling.h"
#include "core/testing/chi_squared.h"
#include "lights/area_light_sampling.h"
#include "lights/light_sample.h"
#include "lights/spherical_sampling.h"

namespace caligo {
namespace {

constexpr double kMinPValue = 1e-3;

// A quad or triangle light as a map from [0,1]^2 with constant Jacobian `area`.
struct Param {
  Light light;
  Vec3 normal;
  double area;
};

Param quad(Vec3 corner, Vec3 e1, Vec3 e2, bool two_sided = false) {
  const Vec3 c = cross(e1, e2);
  return {QuadLight{corner, e1, e2, RGB(1.0f), two_sided}, normalize(c), double(length(c))};
}

Param triangle(Vec3 p0, Vec3 p1, Vec3 p2) {
  const Vec3 c = cross(p1 - p0, p2 - p0);
  return {TriangleLight{p0, p1, p2, RGB(1.0f), false}, normalize(c), 0.5 * double(length(c))};
}

Vec3 point_at(const Param& p, double s, double t) {
  if (const auto* q = std::get_if<QuadLight>(&p.light)) return q->corner + q->edge1 * float(s) + q->edge2 * float(t);
  const auto& tri = std::get<TriangleLight>(p.light);
  const Vec3 b = sample_uniform_triangle({float(s), float(t)});
  return tri.p0 * b.x + tri.p1 * b.y + tri.p2 * b.z;
}

// The inverse of point_at for a point on the light.
Vec2 coords_of(const Param& p, Vec3 x) {
  Vec3 e1, e2, o;
  if (const auto* q = std::get_if<QuadLight>(&p.light)) {
    o = q->corner, e1 = q->edge1, e2 = q->edge2;
  } else {
    const auto& tri = std::get<TriangleLight>(p.light);
    o = tri.p0, e1 = tri.p1 - tri.p0, e2 = tri.p2 - tri.p0;
  }
  const Vec3 d = x - o;
  const double a = dot(e1, e1), b = dot(e1, e2), c = dot(e2, e2), r1 = dot(e1, d), r2 = dot(e2, d);
  const double det = a * c - b * b;
  const double s = (c * r1 - b * r2) / det, t = (a * r2 - b * r1) / det;
  if (std::holds_alternative<QuadLight>(p.light)) return {float(s), float(t)};
  return invert_uniform_triangle({float(1.0 - s - t), float(s), float(t)});
}

// The sampler's density over [0,1]^2: light_pdf (solid angle) times dOmega/dA times area.
double param_density(const Param& p, Vec3 receiver, double s, double t) {
  const Vec3 x = point_at(p, s, t);
  const Vec3 d = x - receiver;
  const double dist2 = length_squared(d);
  const Vec3 wi = d / float(std::sqrt(dist2));
  const double cos_light = std::abs(dot(p.normal, wi));
  return double(light_pdf(p.light, receiver, wi, x, p.normal)) * cos_light / dist2 * p.area;
}

// Midpoint rule over [s0, s1] x [t0, t1] with n x n nodes.
double integrate(const std::function<double(double, double)>& f, double s0, double s1, double t0, double t1,
                 int n) {
  double sum = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) sum += f(s0 + (s1 - s0) * (i + 0.5) / n, t0 + (t1 - t0) * (j + 0.5) / n);
  return sum * (s1 - s0) * (t1 - t0) / (double(n) * n);
}

double total_density(const Param& p, Vec3 receiver, int n = 512) {
  return integrate([&](double s, double t) { return param_density(p, receiver, s, t); }, 0, 1, 0, 1, n);
}

// Pearson's p-value of sample_light's points, binned on a 16 x 16 grid of [0,1]^2, against
// the integral of param_density over each bin.
double chi2_of_sampler(const Param& p, Vec3 receiver, int samples = 100000) {
  constexpr int kBins = 16;
  std::vector<double> observed(kBins * kBins, 0.0), expected(kBins * kBins, 0.0);
  Pcg32 rng(7, 11);
  for (int i = 0; i < samples; ++i) {
    const auto ls = sample_light(p.light, receiver, {rng.next_float(), rng.next_float()});
    if (!ls) continue;
    const Vec2 c = coords_of(p, receiver + ls->wi * ls->distance);
    const int bx = std::clamp(int(c.x * kBins), 0, kBins - 1), by = std::clamp(int(c.y * kBins), 0, kBins - 1);
    observed[size_t(by * kBins + bx)] += 1.0;
  }
  for (int by = 0; by < kBins; ++by)
    for (int bx = 0; bx < kBins; ++bx)
      expected[size_t(by * kBins + bx)] =
          samples * integrate([&](double s, double t) { return param_density(p, receiver, s, t); },
                              double(bx) / kBins, double(bx + 1) / kBins, double(by) / kBins,
                              double(by + 1) / kBins, 8);
  return test_stats::chi2_p_value(observed, expected);
}

// The solid angle the sampler uses from `receiver`; 0 where it samples by area.
double regime_solid_angle(const Param& p, Vec3 receiver) {
  if (const auto* q = std::get_if<QuadLight>(&p.light)) return solid_angle_sampling(*q, receiver).solid_angle;
  return solid_angle_sampling(std::get<TriangleLight>(p.light), receiver).solid_angle;
}

// Receivers in the solid-angle regime: a 2 x 1.5 rectangle from far and from close under
// it (0.2 m: about 5 sr), a parallelogram (two spherical triangles), triangles.
struct Case {
  const char* name;
  Param light;
  Vec3 receiver;
};

std::vector<Case> solid_angle_cases() {
  const Param rect = quad({-1, 2, -0.75f}, {2, 0, 0}, {0, 0, 1.5f});  // faces down (-y)
  const Param skew = quad({-1, 2, -0.75f}, {2, 0, 0}, {0.6f, 0, 1.5f});
  const Param tri = triangle({-1, 2, -1}, {1.5f, 2.2f, -0.5f}, {0, 1.8f, 1.2f});
  // All within 2 bounding radii of the light's centre (kFarRadii).
  return {{"rectangle far", rect, {0.7f, 0.2f, 0.4f}},
          {"rectangle near", rect, {0.1f, 1.8f, 0.05f}},
          {"rectangle oblique", rect, {2, 1.5f, -1.2f}},
          {"parallelogram", skew, {0.2f, 0.9f, 0.3f}},
          {"parallelogram near", skew, {-0.2f, 1.85f, 0.1f}},
          {"triangle", tri, {0.3f, 0.5f, 0.1f}},
          {"triangle near", tri, {0.1f, 1.75f, 0.0f}}};
}

TEST(SphericalSampling, TheCasesAreInTheSolidAngleRegime) {
  for (const Case& c : solid_angle_cases()) {
    SCOPED_TRACE(c.name);
    const double omega = regime_solid_angle(c.light, c.receiver);
    EXPECT_GT(omega, kMinSolidAngle);
    EXPECT_LT(omega, kMaxSolidAngle);
  }
}

// Solid angle by formula against quadrature of cos / d^2 over the light.
TEST(SphericalSampling, SolidAngleMatchesQuadrature) {
  for (const Case& c : solid_angle_cases()) {
    SCOPED_TRACE(c.name);
    const double numeric = integrate(
        [&](double s, double t) {
          const Vec3 d = point_at(c.light, s, t) - c.receiver;
          const double d2 = length_squared(d);
          return std::abs(dot(c.light.normal, d)) / (d2 * std::sqrt(d2)) * c.light.area;
        },
        0, 1, 0, 1, 1024);
    // The sampler's own (spherical angles) and Van Oosterom & Strackee's.
    double sampler, formula;
    if (const auto* q = std::get_if<QuadLight>(&c.light.light)) {
      sampler = quad_solid_angle(*q, c.receiver);
      const Vec3 far = q->corner + q->edge1 + q->edge2;
      formula = spherical_triangle_solid_angle(c.receiver, q->corner, q->corner + q->edge1, far) +
                spherical_triangle_solid_angle(c.receiver, q->corner, far, q->corner + q->edge2);
    } else {
      const auto& t = std::get<TriangleLight>(c.light.light);
      sampler = make_spherical_triangle(c.receiver, t.p0, t.p1, t.p2).solid_angle;
      formula = spherical_triangle_solid_angle(c.receiver, t.p0, t.p1, t.p2);
    }
    EXPECT_NEAR(formula, numeric, 1e-4 * numeric);
    EXPECT_NEAR(sampler, formula, 1e-10 * formula);
  }
}

TEST(SphericalSampling, PdfIntegratesToOneOverTheLight) {
  for (const Case& c : solid_angle_cases()) {
    SCOPED_TRACE(c.name);
    EXPECT_NEAR(total_density(c.light, c.receiver, 1024), 1.0, 1e-4);
  }
}

TEST(SphericalSampling, SamplesFollowTheSolidAngleDensity) {
  for (const Case& c : solid_angle_cases()) {
    SCOPED_TRACE(c.name);
    EXPECT_GT(chi2_of_sampler(c.light, c.receiver), kMinPValue);
  }
}

// The same grid rejects area sampling where solid-angle sampling differs from it: the test
// can tell the two apart (close under the rectangle, where cos/d^2 varies by 50x).
TEST(SphericalSampling, ChiSquaredRejectsAreaSamplingCloseToTheLight) {
  const Case c = solid_angle_cases()[1];
  set_light_sampling_options({.solid_angle = false});
  std::vector<double> observed(256, 0.0), expected(256, 0.0);
  Pcg32 rng(3, 5);
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    const auto ls = sample_light(c.light.light, c.receiver, {rng.next_float(), rng.next_float()});
    ASSERT_TRUE(ls.has_value());
    const Vec2 uv = coords_of(c.light, c.receiver + ls->wi * ls->distance);
    observed[size_t(std::clamp(int(uv.y * 16), 0, 15) * 16 + std::clamp(int(uv.x * 16), 0, 15))] += 1.0;
  }
  set_light_sampling_options({});
  for (int by = 0; by < 16; ++by)
    for (int bx = 0; bx < 16; ++bx)
      expected[size_t(by * 16 + bx)] =
          n * integrate([&](double s, double t) { return param_density(c.light, c.receiver, s, t); }, bx / 16.0,
                        (bx + 1) / 16.0, by / 16.0, (by + 1) / 16.0, 8);
  EXPECT_LT(test_stats::chi2_p_value(observed, expected), 1e-9);
}

// For random receivers (front, back, near the plane, far) and random u: every sample lies on
// the light and light_pdf at it returns the sampler's pdf.
TEST(SphericalSampling, LightPdfEqualsTheSamplersDensity) {
  Pcg32 rng(1, 2);
  int solid = 0, area = 0;
  for (const Case& c : solid_angle_cases()) {
    for (int i = 0; i < 4000; ++i) {
      const float scale = i % 3 == 0 ? 0.3f : i % 3 == 1 ? 3.0f : 80.0f;
      const Vec3 r = c.receiver + Vec3(rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float() - 0.5f) *
                                      (2.0f * scale);
      const auto ls = sample_light(c.light.light, r, {rng.next_float(), rng.next_float()});
      if (!ls) continue;
      const Vec3 x = r + ls->wi * ls->distance;
      const Vec2 uv = coords_of(c.light, x);
      ASSERT_GE(uv.x, -1e-3f);
      ASSERT_LE(uv.x, 1.0f + 1e-3f);
      ASSERT_GE(uv.y, -1e-3f);
      ASSERT_LE(uv.y, 1.0f + 1e-3f);
      const float pdf = light_pdf(c.light.light, r, ls->wi, x, c.light.normal);
      ASSERT_NEAR(pdf, ls->pdf, 1e-4f * ls->pdf) << c.name << " receiver " << r.x << " " << r.y << " " << r.z;
      ++(regime_solid_angle(c.light, r) > 0.0 ? solid : area);
    }
  }
  EXPECT_GT(solid, 1000);  // both regimes were exercised
  EXPECT_GT(area, 1000);
}

TEST(SphericalSampling, NoSampleBehindAOneSidedLight) {
  for (const Case& c : solid_angle_cases()) {
    SCOPED_TRACE(c.name);
    const Vec3 behind = point_at(c.light, 0.3, 0.3) + c.light.normal * -0.5f;
    Pcg32 rng(9, 9);
    for (int i = 0; i < 100; ++i)
      EXPECT_FALSE(sample_light(c.light.light, behind, {rng.next_float(), rng.next_float()}).has_value());
  }
}

// Both sides of each rule, for a 1 x 1 quad facing +y (bounding radius sqrt(1/2)): the
// distance rule on its axis at 2 radii; the stability bounds for receivers within 2 radii:
// 3e-4 sr grazing, 0.8 m beside an edge (height found by bisection), and 6.22 sr over the
// centre (4 asin(1 / (1 + 4 h^2)) = 6.22 at h ~ 9 mm). On each side: the regime the rule
// names, pdf = 1/Omega or the area pdf, the pdf integrates to one and the samples follow it.
TEST(SphericalSampling, AreaSamplingOutsideTheStableRangeAndFarAway) {
  const Param unit = quad({-0.5f, 0, 0.5f}, {1, 0, 0}, {0, 0, -1});  // faces +y
  const auto& q = std::get<QuadLight>(unit.light);
  const float far = float(kFarRadii) * std::sqrt(0.5f);
  // Height above the plane at x = 1.3 where the quad subtends kMinSolidAngle.
  double lo = 1e-6, hi = 0.5;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (quad_solid_angle(q, {1.3f, float(mid), 0}) < kMinSolidAngle ? lo : hi) = mid;
  }
  const float h_min = float(hi);
  ASSERT_GT(h_min, 1e-4f);
  ASSERT_LT(std::hypot(1.3f, h_min), far);  // inside the distance rule
  struct Side {
    Vec3 receiver;
    bool solid_angle;
    int nodes;  // quadrature nodes per side (the density peaks within h of the foot point)
  };
  const Side sides[] = {{{0, 0.99f * far, 0}, true, 256},       {{0, 1.01f * far, 0}, false, 256},
                        {{1.3f, 1.1f * h_min, 0}, true, 256},   {{1.3f, 0.9f * h_min, 0}, false, 256},
                        {{0, 0.02f, 0}, true, 2048},            {{0, 0.005f, 0}, false, 2048}};
  for (const Side& side : sides) {
    SCOPED_TRACE(::testing::Message() << side.receiver.x << " " << side.receiver.y);
    const double omega = quad_solid_angle(q, side.receiver);
    EXPECT_EQ(solid_angle_sampling(q, side.receiver).solid_angle > 0.0, side.solid_angle) << omega;
    const auto ls = sample_light(unit.light, side.receiver, {0.3f, 0.6f});
    ASSERT_TRUE(ls.has_value());
    const Vec3 x = side.receiver + ls->wi * ls->distance;
    const double area_pdf = length_squared(x - side.receiver) / std::abs(dot(unit.normal, ls->wi));
    EXPECT_NEAR(ls->pdf, side.solid_angle ? 1.0 / omega : area_pdf, 1e-4 * ls->pdf);
    EXPECT_NEAR(total_density(unit, side.receiver, side.nodes), 1.0, 2e-3);
    if (side.nodes <= 256) {
      EXPECT_GT(chi2_of_sampler(unit, side.receiver), kMinPValue);
    }
  }
}

// The samplers' solid angles (spherical angles, in double) equal Van Oosterom & Strackee's
// at random receivers, small and distant shapes included (down to ~1e-6 sr).
TEST(SphericalSampling, SamplerSolidAnglesEqualVanOosterom) {
  Pcg32 rng(6, 6);
  for (int i = 0; i < 500; ++i) {
    const float scale = i % 2 ? 1.0f : 300.0f;
    const Vec3 r{(rng.next_float() * 6 - 3) * scale, (rng.next_float() * 6 - 3) * scale,
                 (rng.next_float() * 6 - 3) * scale};
    const Vec3 p0{rng.next_float(), rng.next_float(), rng.next_float()};
    const Vec3 p1 = p0 + Vec3(rng.next_float(), 0.1f, rng.next_float());
    const Vec3 p2 = p0 + Vec3(-rng.next_float(), rng.next_float(), 0.3f);
    const double vo = spherical_triangle_solid_angle(r, p0, p1, p2);
    EXPECT_NEAR(make_spherical_triangle(r, p0, p1, p2).solid_angle, vo, 1e-8 * vo + 1e-15);
  }
}

// The spherical rectangle itself: its solid angle equals the two-triangle formula.
TEST(SphericalSampling, RectangleSolidAngleEqualsTheTrianglePair) {
  const QuadLight q{{-1, 2, -0.75f}, {0, 0, 1.5f}, {2, 0, 0}, RGB(1.0f), false};
  Pcg32 rng(4, 4);
  for (int i = 0; i < 200; ++i) {
    const Vec3 r{rng.next_float() * 6 - 3, rng.next_float() * 6 - 4, rng.next_float() * 6 - 3};
    if (std::abs(r.y - 2) < 1e-2f) continue;
    const SphericalRectangle s = make_spherical_rectangle(r, q.corner, q.edge1, q.edge2);
    const Vec3 far = q.corner + q.edge1 + q.edge2;
    const double vo = spherical_triangle_solid_angle(r, q.corner, q.corner + q.edge1, far) +
                      spherical_triangle_solid_angle(r, q.corner, far, q.corner + q.edge2);
    EXPECT_NEAR(s.solid_angle, vo, 1e-12 + 1e-9 * vo);
  }
}

}  // namespace
}  // namespace caligo
