// The path tracer renders the issue-6 light models (box light, gobo, noise-modulated media)
// with the same emission as delta_arrival: single scattering along one camera ray against
// closed forms and quadrature.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "lights/gobo.h"
#include "render/render.h"
#include "volumes/noise.h"

namespace caligo {
namespace {

constexpr float kSigmaS = 0.3f, kSigmaA = 0.1f, kSigmaT = kSigmaS + kSigmaA;

// One pixel looking down -z from the origin, inside a big homogeneous sphere of fog.
SceneDesc fog_ray_scene() {
  SceneDesc desc;
  desc.file = "test";
  desc.camera = {{0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 1e-3f, {1, 1}};
  desc.volumes.push_back(
      {SphereVolumeShape{Sphere::make({0, 0, 0}, 30.0f, {})}, {RGB(kSigmaA), RGB(kSigmaS)}});
  return desc;
}

// Face at y = 5 over x in [-1, 1], z in [-10, -2], shining down 10 m: the ray is lit for t in [2, 10].
BoxLight box_over_the_ray() {
  return BoxLight{{0, 5, -6}, {0, -1, 0}, {0, 0, -1}, 1.0f, 4.0f, 10.0f, RGB(2.0f)};
}

// The one pixel's green value and its standard error (from the variance AOV).
struct Green {
  double value, se;
};

Green render_green_se(const SceneDesc& desc, int spp, DistanceSampling sampling) {
  const auto scene = Scene::build(desc);
  RenderSettings s = render_settings(desc);
  s.spp = spp;
  s.path.limits.max_volume_bounces = 1;
  s.path.limits.max_bounces = 1;
  s.path.distance_sampling = sampling;
  s.aovs = s.aovs.with(Aov::kVariance);
  const Image image = render(*scene, s).image;
  return {image.rgb(0, 0, 0).g, std::sqrt(double(image.at(0, 0, image.channel_index("variance.G"))))};
}

float render_green(const SceneDesc& desc, int spp, DistanceSampling sampling) {
  return float(render_green_se(desc, spp, sampling).value);
}

// sigma_s e^(-sigma_t t) p E e^(-sigma_t 5) integrated over t in [2, 10], p = 1 / 4 pi.
TEST(LightModels, BoxLightSingleScatteringMatchesTheClosedForm) {
  SceneDesc desc = fog_ray_scene();
  desc.lights.push_back(box_over_the_ray());
  const double expected = kSigmaS * kInv4Pi * 2.0 * std::exp(-kSigmaT * 5.0) *
                          (std::exp(-kSigmaT * 2.0) - std::exp(-kSigmaT * 10.0)) / kSigmaT;
  ASSERT_GT(expected, 5e-3);
  // A homogeneous medium: exact but for the noise, held to 4 standard errors (the variance
  // AOV's; 4096 samples measured a standard error of 1.8 %, too coarse to see a 1 % bias).
  for (DistanceSampling sampling : {DistanceSampling::kDensity, DistanceSampling::kMis}) {
    const Green g = render_green_se(desc, 1 << 18, sampling);
    EXPECT_NEAR(g.value, expected, 4.0 * g.se);
    EXPECT_LT(4.0 * g.se, 0.01 * expected);  // the test can see a 1 % bias
  }
}

// A gobo that is black on the left half of the face and white on the right: the ray runs
// along the face's centre line x = 0, where the bilinear lookup gives exactly half.
TEST(LightModels, BoxLightGoboFiltersTheInScattering) {
  SceneDesc desc = fog_ray_scene();
  BoxLight box = box_over_the_ray();
  box.gobo.image = std::make_shared<const GoboImage>(2, 1, std::vector<RGB>{RGB(0.0f), RGB(1.0f)});
  desc.lights.push_back(box);
  SceneDesc plain = fog_ray_scene();
  plain.lights.push_back(box_over_the_ray());
  const float full = render_green(plain, 2048, DistanceSampling::kDensity);
  ASSERT_GT(full, 5e-3f);
  EXPECT_NEAR(render_green(desc, 2048, DistanceSampling::kDensity), 0.5f * full, 0.01f * full);
}

// Noise-modulated fog: the same integral, with density varying along the camera ray and the
// shadow ray, by nested quadrature of noise_density.
TEST(LightModels, NoiseModulatedMediumMatchesQuadrature) {
  SceneDesc desc = fog_ray_scene();
  const NoiseModulation noise{0.7f, 0.8f, {}, {0.3f, 0.1f, 0.2f}};
  desc.volumes[0].shader.noise = noise;
  desc.lights.push_back(box_over_the_ray());
  const auto density = [&](Vec3 p) { return double(noise_density(noise, p)); };
  const auto optical_depth = [&](Vec3 a, Vec3 b) {
    const int n = 400;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) sum += density(a + (b - a) * ((i + 0.5f) / n));
    return kSigmaT * sum * length(b - a) / n;
  };
  const int n = 2000;
  double expected = 0.0, camera_depth = optical_depth({0, 0, 0}, {0, 0, -2});
  for (int i = 0; i < n; ++i) {
    const float t0 = 2.0f + 8.0f * i / n, t1 = 2.0f + 8.0f * (i + 1) / n;
    const Vec3 x(0, 0, -0.5f * (t0 + t1));
    const double tau = camera_depth + optical_depth({0, 0, -t0}, x);
    expected += kSigmaS * density(x) * std::exp(-tau) * kInv4Pi * 2.0 *
                std::exp(-optical_depth(x, x + Vec3(0, 5, 0))) * (t1 - t0);
    camera_depth += optical_depth({0, 0, -t0}, {0, 0, -t1});
  }
  ASSERT_GT(expected, 1e-3);
  // The noise matters: the homogeneous answer differs by more than the tolerance.
  SceneDesc homogeneous = desc;
  homogeneous.volumes[0].shader.noise.reset();
  EXPECT_GT(std::abs(render_green(homogeneous, 1024, DistanceSampling::kDensity) - expected),
            0.05 * expected);
  // The marcher's own quadrature (steps of 0.25 / scale) and 4096 samples: within 2 %.
  EXPECT_NEAR(render_green(desc, 4096, DistanceSampling::kDensity), expected, 0.02 * expected);
  EXPECT_NEAR(render_green(desc, 4096, DistanceSampling::kMis), expected, 0.02 * expected);
}

}  // namespace
}  // namespace caligo

namespace caligo {
namespace {

// "shadow": false (Arnold's cast_shadows): surfaces do not block the light, so the floor
// under an occluder receives the full inverse-square irradiance; the default blocks it.
// Also the path tracer's reference of a real-time frame, where such lights have no shadow map.
TEST(LightModels, LightsWithoutShadowsAreNotBlockedBySurfaces) {
  for (bool shadow : {true, false}) {
    SceneDesc desc;
    desc.file = "test";
    desc.camera = {{0, 1, 0}, {0, 0, 0}, {0, 0, -1}, 1e-3f, {1, 1}};  // looking straight down at the floor
    desc.materials.push_back({"white", DiffuseBsdf{RGB(0.5f)}, RGB(0.0f), false});
    desc.shapes.push_back({RectangleShape{{-5, 0, -5}, {0, 0, 10}, {10, 0, 0}}, {}, 0, {}});
    desc.shapes.push_back({BoxShape{{-0.5f, 1.5f, -0.5f}, {0.5f, 1.6f, 0.5f}}, {}, 0, {}});
    desc.lights.push_back(PointLight{{0, 3, 0}, RGB(9.0f)});
    desc.light_options.push_back({});
    desc.light_options[0].shadow = shadow;
    const auto scene = Scene::build(desc);
    RenderSettings s = render_settings(desc);
    s.spp = 4;
    s.path.limits.max_bounces = 1;
    const float g = render(*scene, s).image.rgb(0, 0, 0).g;
    const float unblocked = 0.5f / kPi * 9.0f / 9.0f;  // albedo/pi x I cos / d^2, d = 3
    EXPECT_NEAR(g, shadow ? 0.0f : unblocked, 1e-3f * unblocked) << "shadow " << shadow;
  }
}

}  // namespace
}  // namespace caligo
