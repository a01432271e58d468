#include "lights/light_sample.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <optional>

#include "core/math.h"
#include "core/rng.h"
#include "core/sampling.h"

namespace caligo {
namespace {

// Irradiance at `p` on a surface facing `n`, estimated by sampling the light.
double irradiance_by_light_sampling(const Light& light, Vec3 p, Vec3 n, int count) {
  Pcg32 rng(7, 1);
  double sum = 0.0;
  for (int i = 0; i < count; ++i) {
    const auto s = sample_light(light, p, {rng.next_float(), rng.next_float()});
    if (!s) continue;
    EXPECT_TRUE(s->delta || s->pdf > 0.0f);
    sum += s->radiance.average() * std::max(0.0f, dot(n, s->wi)) / s->pdf;
  }
  return sum / count;
}

// The same integral by cosine-weighted hemisphere sampling and ray casting against the light:
// obviously correct, slow, and independent of the light's own sampling code.
template <typename HitLight>
double irradiance_by_hemisphere(Vec3 n, int count, HitLight radiance_along) {
  Pcg32 rng(11, 3);
  const Frame frame = Frame::from_z(n);
  double sum = 0.0;
  for (int i = 0; i < count; ++i) {
    const Vec3 w = frame.to_world(sample_cosine_hemisphere({rng.next_float(), rng.next_float()}));
    sum += radiance_along(w) * kPi;  // L cos / (cos / pi)
  }
  return sum / count;
}

// Ray against the parallelogram corner + s e1 + t e2.
std::optional<float> hit_parallelogram(Vec3 o, Vec3 w, Vec3 corner, Vec3 e1, Vec3 e2) {
  const Vec3 n = cross(e1, e2);
  const float denom = dot(n, w);
  if (std::abs(denom) < 1e-12f) return std::nullopt;
  const float t = dot(n, corner - o) / denom;
  if (t <= 0.0f) return std::nullopt;
  const Vec3 q = o + w * t - corner;
  const float s = dot(q, e1) / dot(e1, e1), u = dot(q, e2) / dot(e2, e2);
  if (s < 0 || s > 1 || u < 0 || u > 1) return std::nullopt;
  return t;
}

TEST(PointLight, InverseSquareLaw) {
  const PointLight light{{0, 4, 0}, RGB(8.0f)};
  const auto s = sample_light(light, {0, 0, 0}, {0.5f, 0.5f});
  ASSERT_TRUE(s);
  EXPECT_TRUE(s->delta);
  EXPECT_FLOAT_EQ(s->radiance.g, 0.5f);
  EXPECT_FLOAT_EQ(s->distance, 4.0f);
  EXPECT_NEAR(power(light), 4.0f * kPi * 8.0f, 1e-3f);
}

// Intensity (W/sr) the spot sends along the unit direction w: the radiance a receiver at
// distance 1 gets from it.
double spot_intensity(const SpotLight& spot, Vec3 w) {
  const auto s = sample_light(spot, spot.position + w, {});
  return s ? double(s->radiance.r) : 0.0;
}

// The falloff documented in light.h: smoothstep in cos(theta) from the outer cone (0) to the
// inner one (1). The power is the intensity integrated over the sphere, here by the midpoint
// rule on a grid in (cos theta, phi) about the cone axis; the integrand is C1 (smoothstep
// meets 0 and 1 with zero slope), so the rule's error is O(h^2), ~1e-7 relative with 8000
// steps in cos theta, and the float evaluation adds ~1e-6. Tolerance 1e-4 relative. For
// this falloff the integral is exact in closed form: 2 pi I (1 - (cos_inner + cos_outer) / 2),
// since smoothstep integrates to 1/2 over its ramp.
TEST(SpotLight, ConeFalloffAndPower) {
  SpotLight spot{{0, 0, 0}, {0, -1, 0}, std::cos(radians(20.0f)), std::cos(radians(30.0f)), RGB(10.0f)};
  const auto on_axis = sample_light(spot, {0, -2, 0}, {});
  ASSERT_TRUE(on_axis);
  EXPECT_FLOAT_EQ(on_axis->radiance.r, 2.5f);
  EXPECT_FALSE(sample_light(spot, {0, 2, 0}, {}));  // behind
  constexpr double kDegree = 3.14159265358979323846 / 180.0;
  const auto along = [](double theta) { return Vec3(float(std::sin(theta)), -float(std::cos(theta)), 0.0f); };
  EXPECT_NEAR(spot_intensity(spot, along(19.0 * kDegree)), 10.0, 1e-5);  // inside the inner cone
  EXPECT_FALSE(sample_light(spot, along(31.0 * kDegree), {}));          // outside the outer cone

  // Mid-cone (25 degrees): t = (cos 25 - cos 30) / (cos 20 - cos 30) = 0.5468,
  // I (3 t^2 - 2 t^3) = 5.700 W/sr.
  const double ci = spot.cos_inner, co = spot.cos_outer;
  const double t = (std::cos(25.0 * kDegree) - co) / (ci - co);
  const double expected_mid = 10.0 * t * t * (3.0 - 2.0 * t);
  EXPECT_NEAR(spot_intensity(spot, along(25.0 * kDegree)), expected_mid, 1e-5 * expected_mid);
  // Where cos theta is half-way between the cones, smoothstep is exactly 1/2.
  EXPECT_NEAR(spot_intensity(spot, along(std::acos(0.5 * (ci + co)))), 5.0, 1e-5 * 5.0);

  const auto integrated_power = [&](const SpotLight& light, int n_cos, int n_phi) {
    double sum = 0.0;
    for (int i = 0; i < n_cos; ++i) {
      const double mu = -1.0 + 2.0 * (i + 0.5) / n_cos;  // cos theta about the axis (-y)
      const double sin_theta = std::sqrt(1.0 - mu * mu);
      for (int j = 0; j < n_phi; ++j) {
        const double phi = 2.0 * kPi * (j + 0.5) / n_phi;
        const Vec3 w(float(sin_theta * std::cos(phi)), -float(mu), float(sin_theta * std::sin(phi)));
        sum += spot_intensity(light, normalize(w));
      }
    }
    return sum * (2.0 / n_cos) * (2.0 * kPi / n_phi);
  };
  const double smooth = integrated_power(spot, 8000, 16);
  EXPECT_NEAR(smooth, 2.0 * kPi * 10.0 * (1.0 - 0.5 * (ci + co)), 1e-4 * smooth);
  std::printf("spot power: integrated %.6f, power() %.6f, closed form %.6f W\n", smooth, double(power(spot)),
              2.0 * kPi * 10.0 * (1.0 - 0.5 * (ci + co)));
  EXPECT_NEAR(power(spot), smooth, 1e-4 * smooth);
  // A hard-edged cone emits I times its solid angle.
  spot.cos_inner = spot.cos_outer;
  // The step costs the midpoint rule up to half a cell, h / 2 = 1.6e-5 in cos theta: 1.2e-4
  // of the cone's 1 - cos_outer = 0.134. Tolerance 2e-4.
  const double hard = integrated_power(spot, 64000, 4);
  EXPECT_NEAR(hard, 10.0 * 2.0 * kPi * (1.0 - co), 2e-4 * hard);
  EXPECT_NEAR(power(spot), 10.0f * 2.0f * kPi * (1.0f - spot.cos_outer), 1e-3f);
}

TEST(SphereLight, IrradianceMatchesTheAnalyticValue) {
  const SphereLight light{{0, 0, 5}, 1.5f, RGB(2.0f)};
  // A surface facing the centre receives E = pi L sin^2(alpha), sin alpha = r / d.
  const double expected = kPi * 2.0 * sqr(1.5f / 5.0f);
  EXPECT_NEAR(irradiance_by_light_sampling(light, {}, {0, 0, 1}, 20000), expected, 1e-3 * expected);
}

TEST(SphereLight, PdfMatchesSampling) {
  const SphereLight light{{1, 2, 5}, 1.0f, RGB(1.0f), true};
  for (Vec3 receiver : {Vec3(0, 0, 0), Vec3(1, 2, 5.2f)}) {  // outside, then inside
    Pcg32 rng(3, 4);
    for (int i = 0; i < 100; ++i) {
      const auto s = sample_light(light, receiver, {rng.next_float(), rng.next_float()});
      ASSERT_TRUE(s);
      const Vec3 p = receiver + s->wi * s->distance;
      EXPECT_NEAR(length(p - light.center), 1.0f, 1e-3f);
      const float pdf = light_pdf(light, receiver, s->wi, p, normalize(p - light.center));
      EXPECT_NEAR(pdf, s->pdf, 1e-3f * s->pdf);
    }
  }
}

TEST(QuadLight, LightSamplingAgreesWithHemisphereSampling) {
  const QuadLight light{{-0.5f, 2, -1}, {2, 0, 0}, {0, 0, 1.5f}, RGB(3.0f)};
  // cross(e1, e2) = (0, 0, 0) x ... = -y: faces down, towards the receiver.
  const Vec3 p(0.2f, 0, 0.1f), n = normalize(Vec3(0.3f, 1, 0));
  const double by_light = irradiance_by_light_sampling(light, p, n, 40000);
  const double by_hemisphere = irradiance_by_hemisphere(n, 400000, [&](Vec3 w) {
    return hit_parallelogram(p, w, light.corner, light.edge1, light.edge2) ? 3.0 : 0.0;
  });
  EXPECT_NEAR(by_light, by_hemisphere, 0.01 * by_hemisphere);
  // One-sided: from above it is dark.
  EXPECT_FALSE(sample_light(light, {0, 4, 0}, {0.5f, 0.5f}));
}

TEST(TriangleLight, LightSamplingAgreesWithHemisphereSampling) {
  const TriangleLight light{{-1, 1, -1}, {0, 1, 2}, {1.5f, 1, -1}, RGB(1.0f), true};
  const Vec3 p(0, 0, 0), n(0, 1, 0);
  const Vec3 e1 = light.p1 - light.p0, e2 = light.p2 - light.p0;
  const double by_light = irradiance_by_light_sampling(light, p, n, 40000);
  const double by_hemisphere = irradiance_by_hemisphere(n, 400000, [&](Vec3 w) {
    // The triangle lies inside the parallelogram p0 + s e1 + t e2.
    const auto t = hit_parallelogram(p, w, light.p0, e1, e2);
    if (!t) return 0.0;
    const Vec3 q = p + w * *t - light.p0;
    // Inside the triangle iff its barycentrics are non-negative.
    const Vec3 c = cross(e1, e2);
    const float b1 = dot(cross(q, e2), c) / dot(c, c), b2 = dot(cross(e1, q), c) / dot(c, c);
    return (b1 >= 0 && b2 >= 0 && b1 + b2 <= 1) ? 1.0 : 0.0;
  });
  EXPECT_NEAR(by_light, by_hemisphere, 0.01 * by_hemisphere);
}

// Ray against the disk light's polygon: the plane, then the sector's triangle.
bool hits_disk(const DiskLight& d, Vec3 o, Vec3 w) {
  const float denom = dot(d.normal, w);
  if (std::abs(denom) < 1e-12f) return false;
  const float t = dot(d.normal, d.center - o) / denom;
  if (t <= 0.0f) return false;
  const Vec3 q = o + w * t;
  for (int k = 0; k < DiskLight::kSides; ++k) {
    const Vec3 a = d.vertex(k) - d.center, b = d.vertex(k + 1) - d.center, x = q - d.center;
    const float area = dot(cross(a, b), d.normal);
    const float s = dot(cross(x, b), d.normal) / area, u = dot(cross(a, x), d.normal) / area;
    if (s >= 0 && u >= 0 && s + u <= 1) return true;
  }
  return false;
}

TEST(DiskLight, LightSamplingAgreesWithHemisphereSampling) {
  const DiskLight light{{0.3f, 2, -0.2f}, normalize(Vec3(0.2f, -1, 0.1f)), 1.3f, RGB(2.0f)};
  const Vec3 p(0, 0, 0), n = normalize(Vec3(-0.3f, 1, 0.2f));
  const double by_light = irradiance_by_light_sampling(light, p, n, 40000);
  const double by_hemisphere =
      irradiance_by_hemisphere(n, 400000, [&](Vec3 w) { return hits_disk(light, p, w) ? 2.0 : 0.0; });
  // The hemisphere estimate's standard error is 0.25 % here; 1 % is 4 of them.
  EXPECT_NEAR(by_light, by_hemisphere, 0.01 * by_hemisphere);
  // One-sided: from behind it is dark.
  EXPECT_FALSE(sample_light(light, {0, 4, 0}, {0.5f, 0.5f}));
}

TEST(DiskLight, PdfMatchesSamplingAndTheSurfaceIsTheSampledPolygon) {
  const DiskLight light{{1, 2, 3}, normalize(Vec3(1, 1, -1)), 0.7f, RGB(1.0f), true};
  const Vec3 receiver(-1, 0, 5);
  Pcg32 rng(5, 6);
  for (int i = 0; i < 200; ++i) {
    const auto s = sample_light(light, receiver, {rng.next_float(), rng.next_float()});
    ASSERT_TRUE(s);
    const Vec3 q = receiver + s->wi * s->distance;
    EXPECT_NEAR(dot(q - light.center, light.normal), 0.0f, 1e-5f);
    EXPECT_LE(length(q - light.center), light.radius * 1.0001f);
    EXPECT_NEAR(light_pdf(light, receiver, s->wi, q, light.normal), s->pdf, 1e-4f * s->pdf);
  }
  const auto surface = visible_geometry(light);
  ASSERT_TRUE(surface);
  const auto& fan = std::get<VisibleTriangles>(surface->shape);
  ASSERT_EQ(fan.indices.size(), 3u * DiskLight::kSides);
  double area = 0.0;
  for (size_t t = 0; t < fan.indices.size(); t += 3) {
    const Vec3 a = fan.positions[fan.indices[t]], b = fan.positions[fan.indices[t + 1]],
               c = fan.positions[fan.indices[t + 2]];
    const Vec3 ng = cross(b - a, c - a);
    EXPECT_GT(dot(ng, light.normal), 0.0f);  // wound towards the emitting side
    area += 0.5 * length(ng);
  }
  EXPECT_NEAR(area, light.area(), 1e-5 * light.area());
  // The polygon's area against the circle's: 64 sides leave 0.16 %.
  EXPECT_NEAR(light.area() / (kPi * sqr(light.radius)), 1.0 - 0.0016, 1e-4);
  EXPECT_NEAR(power(light), 2.0 * kPi * light.area(), 1e-5 * power(light));
}

TEST(EnvironmentLight, UniformRadianceGivesPiL) {
  const EnvironmentLight env{RGB(0.7f)};
  EXPECT_NEAR(irradiance_by_light_sampling(env, {}, {0, 1, 0}, 200000), kPi * 0.7, 0.01 * kPi * 0.7);
  EXPECT_FLOAT_EQ(light_pdf(env, {}, {0, 1, 0}, {}, {}), 1.0f / (4.0f * kPi));
}

TEST(DirectionalLight, SunDiskDeliversItsIrradiance) {
  DirectionalLight sun{normalize(Vec3(0, -1, -1)), RGB(5.0f), std::cos(radians(2.0f))};
  EXPECT_NEAR(irradiance_by_light_sampling(sun, {}, normalize(Vec3(0, 1, 1)), 20000), 5.0, 0.005 * 5.0);
  EXPECT_TRUE(escaped_radiance(sun, normalize(Vec3(0, 1, 1))).r > 0.0f);
  EXPECT_TRUE(escaped_radiance(sun, Vec3(0, 1, 0)).is_black());
  sun.cos_angular_radius = 1.0f;
  EXPECT_TRUE(is_delta(sun));
  const auto s = sample_light(sun, {}, {0.3f, 0.3f});
  ASSERT_TRUE(s);
  EXPECT_TRUE(s->delta);
  EXPECT_FLOAT_EQ(s->radiance.r, 5.0f);
}

TEST(Light, Classification) {
  EXPECT_TRUE(is_delta(PointLight{}));
  EXPECT_FALSE(is_delta(QuadLight{}));
  EXPECT_TRUE(is_infinite(EnvironmentLight{}));
  EXPECT_FALSE(is_infinite(SphereLight{}));
  // A box light is parallel light that starts inside the scene: delta, but not at infinity.
  EXPECT_TRUE(is_delta(BoxLight{}));
  EXPECT_FALSE(is_infinite(BoxLight{}));
  EXPECT_TRUE(is_delta(SpotLight{}));
  EXPECT_TRUE(is_infinite(DirectionalLight{}));
}

TEST(Light, EscapedRadianceComesOnlyFromLightsAtInfinity) {
  EXPECT_EQ(escaped_radiance(BoxLight{{}, {0, -1, 0}, {0, 0, 1}, 1, 1, 10, RGB(3.0f)}, {0, 1, 0}), RGB(0.0f));
  EXPECT_EQ(escaped_radiance(EnvironmentLight{RGB(2.0f)}, {0, 1, 0}), RGB(2.0f));
  EXPECT_EQ(light_pdf(BoxLight{}, {}, {0, 1, 0}, {}, {}), 0.0f);
}

}  // namespace
}  // namespace caligo
