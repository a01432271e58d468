// The reference ladder (reference.h): first checked against closed forms and quadrature,
// then used to check the production path tracer. Each comparison states its tolerance and
// sample counts; the counts keep the Monte Carlo error of both sides well inside it.
#include "integrators/reference.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "render/render.h"

namespace caligo {
namespace {

// ---- scene building ----

// 2.44 m from the origin: just outside the radius-2 media centred there.
constexpr Vec3 kNearbyPoint{0.9f, 1.6f, -1.6f};

VolumeShader shader(RGB sigma_a, RGB sigma_s, PhaseFunction phase = IsotropicPhase{},
                    DensityField field = ConstantDensity{}, float density = 1.0f, float step_size = 0.0f) {
  return VolumeShader{sigma_a, sigma_s, RGB(0.0f), density, phase, field, std::nullopt, step_size};
}

VolumePrimitive sphere_volume(Vec3 center, float radius, const VolumeShader& s) {
  return {SphereVolumeShape{Sphere::make(center, radius, {})}, s};
}

VolumePrimitive box_volume(Vec3 lo, Vec3 hi, const VolumeShader& s) {
  return {BoxVolumeShape{Transform(), lo, hi}, s};
}

SceneDesc camera_at(Vec3 position, Vec3 look_at, Vec2i resolution, float fov_degrees = 45.0f) {
  SceneDesc desc;
  desc.file = "test";
  desc.camera.position = position;
  desc.camera.look_at = look_at;
  desc.camera.resolution = resolution;
  desc.camera.fov_degrees = fov_degrees;
  return desc;
}

// ---- image statistics ----

RGB mean_of(const std::vector<RGB>& pixels) {
  double r = 0, g = 0, b = 0;
  for (const RGB& p : pixels) r += p.r, g += p.g, b += p.b;
  const double n = double(pixels.size());
  return RGB(float(r / n), float(g / n), float(b / n));
}

std::vector<RGB> pixels_of(const Image& image) {
  std::vector<RGB> out;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) out.push_back(image.rgb(x, y, 0));
  return out;
}

// Means of square blocks of `block` x `block` pixels, row-major.
std::vector<RGB> block_means(const std::vector<RGB>& pixels, Vec2i resolution, int block) {
  std::vector<RGB> out;
  for (int by = 0; by + block <= resolution.y; by += block)
    for (int bx = 0; bx + block <= resolution.x; bx += block) {
      RGB sum;
      for (int y = by; y < by + block; ++y)
        for (int x = bx; x < bx + block; ++x) sum += pixels[size_t(y) * size_t(resolution.x) + size_t(x)];
      out.push_back(sum / float(block * block));
    }
  return out;
}

std::string str(RGB c) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.5f %.5f %.5f)", double(c.r), double(c.g), double(c.b));
  return buf;
}

float relative_difference(float a, float b) { return std::abs(a - b) / std::max(std::abs(b), 1e-12f); }

float max_relative_difference(RGB a, RGB b) {
  float worst = 0.0f;
  for (int c = 0; c < 3; ++c) worst = std::max(worst, relative_difference(a[c], b[c]));
  return worst;
}

void expect_means_close(RGB estimate, RGB reference, float tolerance, const std::string& what) {
  const float diff = max_relative_difference(estimate, reference);
  std::printf("  [%s] estimate %s reference %s: max channel difference %.2f%%\n", what.c_str(),
              str(estimate).c_str(), str(reference).c_str(), 100.0 * double(diff));
  EXPECT_LE(diff, tolerance) << what << ": estimate " << str(estimate) << " reference " << str(reference);
}

// Every block's channels agree within `tolerance` of the larger of that block's reference
// value and the reference image mean (dim blocks carry little signal and relatively large noise).
void expect_blocks_close(const std::vector<RGB>& production, const std::vector<RGB>& reference,
                         Vec2i resolution, int block, float tolerance, const std::string& what) {
  const auto a = block_means(production, resolution, block), b = block_means(reference, resolution, block);
  const RGB mean = mean_of(reference);
  float worst = 0.0f;
  for (size_t i = 0; i < a.size(); ++i)
    for (int c = 0; c < 3; ++c)
      worst = std::max(worst, std::abs(a[i][c] - b[i][c]) / std::max(b[i][c], mean[c]));
  std::printf("  [%s] worst of %zu %dx%d blocks: %.2f%%\n", what.c_str(), a.size(), block, block,
              100.0 * double(worst));
  EXPECT_LE(worst, tolerance) << what;
}

struct ProductionRun {
  int spp = 64;
  int max_volume_bounces = 64;
  DistanceSampling distance_sampling = DistanceSampling::kMis;
  uint64_t seed = 1;
};

std::vector<RGB> render_production(const Scene& scene, const SceneDesc& desc, const ProductionRun& run) {
  RenderSettings settings = render_settings(desc);
  settings.spp = run.spp;
  settings.path.limits.max_volume_bounces = run.max_volume_bounces;
  settings.path.distance_sampling = run.distance_sampling;
  settings.seed = run.seed;
  return pixels_of(render(scene, settings).image);
}

// Sample counts of the production-vs-ladder comparisons. Measured standard errors of the
// image mean (over seeds): production single scattering ~0.1% at 64 spp, multiple ~0.35% at
// 256 spp; ladder single scattering ~0.3% at 256 x 4, delta tracking ~0.5% per channel at 4096.
// The mean comparisons hold to 4 combined standard errors: single scattering
// 4 x hypot(0.1, 0.3) % = 1.3 %; multiple scattering's 2 % is 3.3 x hypot(0.35, 0.5) %. A block
// of a 24 x 24 image holds a ninth of its pixels, so its standard error is 3 times the image's:
// blocks hold to 4 of those, 3.8 % (single) and 7.3 % (multiple); measured worst 1.2 % and 4.3 %.
constexpr float kSingleMeanTolerance = 0.013f, kMultipleMeanTolerance = 0.02f;
constexpr float kSingleBlockTolerance = 0.038f, kMultipleBlockTolerance = 0.073f;
constexpr ProductionRun kSingleProduction{64, 1};
constexpr ProductionRun kMultipleProduction{256, 64};
constexpr ReferenceOptions kSingleReference{ReferenceEstimator::kSingleScattering, 256, {64, 64}, 4, 2};
constexpr ReferenceOptions kDeltaReference{ReferenceEstimator::kDeltaTracking, 4096, {64, 64}, 1, 2};

// ---- rung 1: transmittance ----

TEST(ReferenceLadder, TransmittanceOfHomogeneousMediaIsExact) {
  SceneDesc desc = camera_at({0, 0, 5}, {0, 0, 0}, {4, 4});
  const RGB box_sigma_t(0.3f, 0.5f, 0.7f), sphere_sigma_t(0.2f, 0.1f, 0.05f);
  desc.volumes.push_back(
      box_volume({-1, -1, -1}, {1, 1, 1}, shader(box_sigma_t * 0.25f, box_sigma_t * 0.75f)));
  desc.volumes.push_back(sphere_volume({4, 0, 0}, 2.0f, shader(sphere_sigma_t, RGB(0.0f))));
  const auto scene = Scene::build(desc);
  const auto expect_exp = [](RGB tr, RGB optical_depth) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(tr[c], std::exp(-optical_depth[c]), 1e-4f) << "channel " << c;
  };
  Ray along_x{{-3, 0.5f, 3.0f}, {1, 0, 0}, 0.0f, kInfinity};  // misses both
  expect_exp(reference_transmittance(*scene, along_x, kInfinity, 8), RGB(0.0f));
  along_x.origin = {-3, 0.2f, 0.1f};  // box [-1, 1] and the sphere's chord through (4, 0.2, 0.1)
  const float chord = 2.0f * std::sqrt(4.0f - 0.2f * 0.2f - 0.1f * 0.1f);
  expect_exp(reference_transmittance(*scene, along_x, kInfinity, 8),
             box_sigma_t * 2.0f + sphere_sigma_t * chord);
  // Stopping inside the box: 1.5 m of it.
  expect_exp(reference_transmittance(*scene, along_x, 3.5f, 8), box_sigma_t * 1.5f);
  // tmin inside the box, and a non-unit direction: t counts in units of |direction|.
  Ray scaled{{-3, 0.2f, 0.1f}, {2, 0, 0}, 1.25f, kInfinity};
  expect_exp(reference_transmittance(*scene, scaled, 1.75f, 8), box_sigma_t * 1.0f);
}

// ---- rung 2: single scattering ----

// One camera ray inside a large homogeneous sphere with a point light off the ray, against
// the single-scattering integral written out and integrated by Simpson's rule:
//   L = int_0^6 sigma_s exp(-sigma_t t) p(cos) I exp(-sigma_t r(t)) / r(t)^2 dt,
// cos = dot(d, wi) (light travels along -wi, then along -d towards the camera).
TEST(ReferenceLadder, SingleScatteringMatchesQuadrature) {
  const float sigma_s = 0.25f, sigma_a = 0.05f, sigma_t = sigma_s + sigma_a, g = 0.3f, intensity = 3.0f;
  const Vec3 light_position{1.0f, 0.6f, 0.3f};
  SceneDesc desc = camera_at({0, 0, 5}, {0, 0, 0}, {4, 4});
  desc.volumes.push_back(
      sphere_volume({0, 0, 0}, 6.0f, shader(RGB(sigma_a), RGB(sigma_s), HenyeyGreensteinPhase{g})));
  desc.lights.push_back(PointLight{light_position, RGB(intensity)});
  const auto scene = Scene::build(desc);
  const Ray ray{{0, 0, 0}, normalize(Vec3(1.0f, 0.0f, 0.2f)), 0.0f, kInfinity};

  const auto integrand = [&](double t) {
    const Vec3 x = ray.at(float(t));
    const Vec3 to_light = light_position - x;
    const double r = length(to_light);
    const double cos_theta = dot(ray.direction, to_light) / r;
    const double hg = (1 - g * g) / (4 * M_PI * std::pow(1 + g * g - 2 * g * cos_theta, 1.5));
    return sigma_s * std::exp(-sigma_t * t) * hg * intensity * std::exp(-sigma_t * r) / (r * r);
  };
  const int n = 20000;
  const double h = 6.0 / n;
  double expected = integrand(0.0) + integrand(6.0);
  for (int i = 1; i < n; ++i) expected += (i % 2 ? 4 : 2) * integrand(i * h);
  expected *= h / 3;

  Pcg32 rng(7, 11);
  const int calls = 200000;
  double sum = 0, sum2 = 0;
  for (int i = 0; i < calls; ++i) {
    const double v = reference_single_scattering(*scene, ray, 1, rng).g;
    sum += v, sum2 += v * v;
  }
  const double mean = sum / calls, std_error = std::sqrt((sum2 / calls - mean * mean) / calls);
  std::printf("  quadrature %.6f, estimate %.6f +- %.6f (%.2f%%)\n", expected, mean, std_error,
              100.0 * (mean - expected) / expected);
  EXPECT_NEAR(mean, expected, 0.01 * expected);
}

// Rung 3 against rung 2: delta tracking stopped after one scattering event is single scattering.
TEST(ReferenceLadder, DeltaTrackingWithOneBounceIsSingleScattering) {
  SceneDesc desc = camera_at({0, 0, -6}, {0, 0, 0}, {12, 12});
  desc.volumes.push_back(sphere_volume(
      {0, 0, 0}, 2.0f, shader(RGB(0.05f, 0.1f, 0.2f), RGB(0.5f, 0.4f, 0.2f), HenyeyGreensteinPhase{0.5f})));
  desc.lights.push_back(PointLight{kNearbyPoint, RGB(5.0f)});
  const auto scene = Scene::build(desc);
  ReferenceOptions single{ReferenceEstimator::kSingleScattering, 256, {64, 64}, 4, 3};
  ReferenceOptions delta{ReferenceEstimator::kDeltaTracking, 8192, {.max_bounces = 64, .max_volume_bounces = 1}, 1, 4};
  expect_means_close(reference_mean_radiance(*scene, desc.camera.resolution, delta),
                     reference_mean_radiance(*scene, desc.camera.resolution, single), 0.02f,
                     "delta(1) vs single");
}

// Rung 3 on surfaces: a point light at the centre of a diffuse sphere (no media) is a furnace,
// L = rho I / (pi R^2 (1 - rho)) with all bounces.
TEST(ReferenceLadder, DeltaTrackingDiffuseFurnace) {
  const float rho = 0.5f, intensity = 4.0f, radius = 2.0f;
  SceneDesc desc = camera_at({0.3f, 0.2f, 0}, {1, 0.5f, 0.2f}, {8, 8});
  desc.materials.push_back({"wall", DiffuseBsdf{RGB(rho)}, RGB(0.0f), false});
  desc.shapes.push_back({SphereShape{{0, 0, 0}, radius}, {}, 0});
  desc.lights.push_back(PointLight{{0, 0, 0}, RGB(intensity)});
  const auto scene = Scene::build(desc);
  ReferenceOptions options{ReferenceEstimator::kDeltaTracking, 128, {.max_bounces = 64, .max_volume_bounces = 200}, 1, 5};
  const RGB mean = reference_mean_radiance(*scene, desc.camera.resolution, options);
  const float expected = rho * intensity / (kPi * radius * radius * (1.0f - rho));
  EXPECT_NEAR(mean.average(), expected, 0.02f * expected);
}

// Rung 3 with a dielectric: a glass sphere in a uniform environment, no absorption, is a
// furnace: every path ends in the environment, and radiance enters (1/eta^2) and leaves
// (eta^2) the glass unchanged, so every pixel sees exactly the environment's radiance (paths
// cut by max_bounces lose a negligible part: Fresnel ~4% per internal reflection).
TEST(ReferenceLadder, DeltaTrackingGlassFurnace) {
  SceneDesc desc = camera_at({0, 0, -4}, {0, 0, 0}, {8, 8}, 25.0f);
  desc.materials.push_back({"glass", DielectricBsdf{1.5f}, RGB(0.0f), false});
  desc.shapes.push_back({SphereShape{{0, 0, 0}, 1.0f}, {}, 0});
  desc.lights.push_back(EnvironmentLight{RGB(0.5f)});
  const auto scene = Scene::build(desc);
  ReferenceOptions options{ReferenceEstimator::kDeltaTracking, 64, {64, 64}, 1, 5};
  const RGB mean = reference_mean_radiance(*scene, desc.camera.resolution, options);
  // The channel picked per sample is the only noise: 3x in one channel, 0 in the others.
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(mean[c], 0.5f, 0.05f) << c;
  EXPECT_NEAR(mean.average(), 0.5f, 1e-3f);
}

// ---- production against the ladder ----

enum class FogLight { kNearbyPoint, kSphereInside };

// A homogeneous fog sphere (radius 2, sigma_s 0.4, sigma_a 0.05) seen from outside, lit by a
// point light 0.44 m outside it or by a small sphere light inside it, off centre. (A point
// light inside a medium gives every estimator that reaches it from collision or uniformly
// sampled points infinite variance: E[(1/r^2)^2] over the volume diverges like the integral
// of dr / r^2. Such estimates converge from below at a crawl, so the ladder avoids them.)
SceneDesc fog_sphere_scene(PhaseFunction phase, FogLight light = FogLight::kNearbyPoint) {
  SceneDesc desc = camera_at({0, 0, -6}, {0, 0, 0}, {24, 24});
  desc.volumes.push_back(sphere_volume({0, 0, 0}, 2.0f, shader(RGB(0.05f), RGB(0.4f), phase)));
  if (light == FogLight::kNearbyPoint) desc.lights.push_back(PointLight{kNearbyPoint, RGB(5.0f)});
  if (light == FogLight::kSphereInside) {
    // Out of frame: seen directly, the light would dominate the image mean with the noise of
    // its pixel coverage and of the transmittance in front of it (both estimators sample it).
    desc.lights.push_back(SphereLight{{1.4f, -0.8f, 0.3f}, 0.25f, RGB(4.0f)});
    desc.camera.fov_degrees = 18.0f;
  }
  return desc;
}

TEST(ProductionVsReference, SingleScatteringFogSphere) {
  for (const PhaseFunction phase :
       {PhaseFunction(IsotropicPhase{}), PhaseFunction(HenyeyGreensteinPhase{0.5f})}) {
    const SceneDesc desc = fog_sphere_scene(phase);
    const auto scene = Scene::build(desc);
    const Vec2i res = desc.camera.resolution;
    const auto production = render_production(*scene, desc, kSingleProduction);
    const auto reference = reference_image(*scene, res, kSingleReference);
    const std::string what =
        std::holds_alternative<IsotropicPhase>(phase) ? "single, isotropic" : "single, HG 0.5";
    expect_means_close(mean_of(production), mean_of(reference), kSingleMeanTolerance, what);
    expect_blocks_close(production, reference, res, 8, kSingleBlockTolerance, what);
  }
}

TEST(ProductionVsReference, MultipleScatteringFogSphere) {
  for (const FogLight light : {FogLight::kNearbyPoint, FogLight::kSphereInside}) {
    const SceneDesc desc = fog_sphere_scene(HenyeyGreensteinPhase{0.5f}, light);
    const auto scene = Scene::build(desc);
    const Vec2i res = desc.camera.resolution;
    const auto production = render_production(*scene, desc, kMultipleProduction);
    const auto reference = reference_image(*scene, res, kDeltaReference);
    const std::string what =
        light == FogLight::kNearbyPoint ? "multiple, point light" : "multiple, sphere light";
    expect_means_close(mean_of(production), mean_of(reference), kMultipleMeanTolerance, what);
    expect_blocks_close(production, reference, res, 8, kMultipleBlockTolerance, what);
  }
}

// Two overlapping boxes of chromatic media under a spot light and a dim uniform environment
// (seen directly and through the boxes). `phase_b` is the second box's phase function.
SceneDesc chromatic_boxes_scene(PhaseFunction phase_b) {
  SceneDesc desc = camera_at({0.5f, 0.5f, -6}, {0, 0, 0}, {24, 24}, 40.0f);
  desc.volumes.push_back(
      box_volume({-1.5f, -1, -1}, {0.5f, 1, 1},
                 shader(RGB(0.05f, 0.1f, 0.2f), RGB(0.9f, 0.4f, 0.1f), HenyeyGreensteinPhase{0.4f})));
  desc.volumes.push_back(box_volume({-0.5f, -0.8f, -0.8f}, {1.5f, 0.8f, 0.8f},
                                    shader(RGB(0.1f, 0.05f, 0.02f), RGB(0.1f, 0.4f, 0.8f), phase_b)));
  desc.lights.push_back(
      SpotLight{{0.2f, 3, 0}, {0, -1, 0}, std::cos(radians(25.0f)), std::cos(radians(35.0f)), RGB(20.0f)});
  desc.lights.push_back(EnvironmentLight{RGB(0.05f, 0.06f, 0.08f)});
  return desc;
}

// Both boxes share one phase function, so production's phase mixture (lobes weighted by
// average sigma_s) equals the exact per-channel one.
TEST(ProductionVsReference, MultipleScatteringChromaticBoxes) {
  const SceneDesc desc = chromatic_boxes_scene(HenyeyGreensteinPhase{0.4f});
  const auto scene = Scene::build(desc);
  const Vec2i res = desc.camera.resolution;
  const auto production = render_production(*scene, desc, kMultipleProduction);
  const auto reference = reference_image(*scene, res, kDeltaReference);
  expect_means_close(mean_of(production), mean_of(reference), kMultipleMeanTolerance, "multiple, chromatic boxes");
  expect_blocks_close(production, reference, res, 8, kMultipleBlockTolerance, "multiple, chromatic boxes");
}

// Where primitives with different phase functions and differently coloured sigma_s overlap,
// light in channel c scatters by sum_i sigma_s,i[c] phase_i / sigma_s[c]: the phase mixture
// differs per channel. This test found production weighting lobes by average sigma_s (the
// overlap block's red 7.5-8% low, blue 7-8% high); lobes now carry RGB weights.
TEST(ProductionVsReference, MixedPhasesInChromaticOverlap) {
  const SceneDesc desc = chromatic_boxes_scene(HenyeyGreensteinPhase{-0.6f});
  const auto scene = Scene::build(desc);
  const Vec2i res = desc.camera.resolution;
  const auto production = render_production(*scene, desc, kMultipleProduction);
  const auto reference = reference_image(*scene, res, kDeltaReference);
  expect_means_close(mean_of(production), mean_of(reference), 0.02f, "multiple, mixed phases");
  expect_blocks_close(production, reference, res, 8, 0.04f, "multiple, mixed phases");
}

// A heterogeneous puff: density (1 - r^2)^2. Production marches it in 0.02 m steps (the
// midpoint-rule bias of that is far below the tolerance).
TEST(ProductionVsReference, MultipleScatteringHeterogeneousPuff) {
  SceneDesc desc = camera_at({0, 0, -6}, {0, 0, 0}, {16, 16});
  desc.volumes.push_back(sphere_volume(
      {0, 0, 0}, 2.0f,
      shader(RGB(0.1f), RGB(0.8f), HenyeyGreensteinPhase{0.3f}, RadialFalloffDensity{2.0f}, 2.0f, 0.02f)));
  desc.lights.push_back(PointLight{kNearbyPoint, RGB(5.0f)});
  const auto scene = Scene::build(desc);
  const Vec2i res = desc.camera.resolution;
  const auto production = render_production(*scene, desc, kMultipleProduction);
  const auto reference = reference_image(*scene, res, kDeltaReference);
  expect_means_close(mean_of(production), mean_of(reference), 0.03f, "multiple, heterogeneous");
  expect_blocks_close(production, reference, res, 8, 0.10f, "multiple, heterogeneous");
}

// Density, equiangular and MIS distance sampling are all unbiased: the same image mean,
// and the ladder's, for single scattering (where next-event estimation is everything). With
// the sphere light, production's phase-sampled rays that reach it carry the other half of
// its light-sampling MIS; the light is out of frame, so the ladder's scope matches.
TEST(ProductionVsReference, DistanceSamplingStrategiesAgree) {
  for (const FogLight light : {FogLight::kNearbyPoint, FogLight::kSphereInside}) {
    const SceneDesc desc = fog_sphere_scene(HenyeyGreensteinPhase{0.5f}, light);
    const auto scene = Scene::build(desc);
    const RGB reference = reference_mean_radiance(*scene, desc.camera.resolution, kSingleReference);
    const std::pair<DistanceSampling, const char*> strategies[] = {
        {DistanceSampling::kDensity, "density"},
        {DistanceSampling::kEquiangular, "equiangular"},
        {DistanceSampling::kMis, "mis"}};
    for (const auto& [strategy, name] : strategies) {
      const RGB mean = mean_of(render_production(*scene, desc, {kSingleProduction.spp, 1, strategy}));
      const std::string what =
          (light == FogLight::kNearbyPoint ? "single, point light, " : "single, sphere light, ");
      expect_means_close(mean, reference, 0.02f, what + name);
    }
  }
}

}  // namespace
}  // namespace caligo
