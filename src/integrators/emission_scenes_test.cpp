// Volume emission as a light (volumes/emission_sampler.h, integrators/emission_direct.h): the
// sampler's densities against what it samples, and whole renders with and without it, which
// must agree in the mean (MIS splits the emission between connections and bounce rays) while the
// connections take the noise out of what a flame lights. Tolerances are 4 standard errors of the
// estimate's own sample.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/math.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "core/test_stat.h"
#include "integrators/test_grids.h"
#include "integrators/test_scenes.h"
#include "render/film.h"
#include "render/render.h"
#include "volumes/emission_sampler.h"

namespace caligo {
namespace {

using testing::grid_primitive;
using testing::make_grid;

using testing::Stat;

// A 24^3 grid of 0.1 m voxels whose density ramps along x, emitting 2 per unit density: blocks
// differ in weight, so a sampler that ignored its own weights would fail the checks below.
VolumePrimitive ramp_emitter() {
  const auto grid = make_grid([](int i, int, int) { return 0.2f + float(i) / 24.0f; }, 24, 0.1f, Vec3(0.0f));
  VolumePrimitive v = grid_primitive(grid, RGB(1.0f), RGB(0.5f));
  v.shader.emission = RGB(2.0f, 1.0f, 0.5f);
  return v;
}

// E[g(y) / pdf(y)] over sampled points is the volume integral of g wherever the density is
// positive: here the indicator of a box well inside the emitter, whose volume is known.
TEST(EmissionSampler, SampledPointsFollowTheirDensity) {
  const VolumeScene volumes({ramp_emitter()});
  VolumeContext context;
  const EmissionSampler sampler = EmissionSampler::build(volumes, context);
  ASSERT_FALSE(sampler.empty());
  Pcg32 rng(3, 5);
  const Vec3 lo(0.35f, 0.5f, 0.4f), hi(1.15f, 1.3f, 1.6f);
  Stat box;
  for (int i = 0; i < 40000; ++i) {
    const auto y = sampler.sample(rng.next_float(), {rng.next_float(), rng.next_float(), rng.next_float()});
    ASSERT_TRUE(y.has_value());
    ASSERT_FLOAT_EQ(y->pdf, sampler.pdf(y->p));
    const bool inside = y->p.x >= lo.x && y->p.x < hi.x && y->p.y >= lo.y && y->p.y < hi.y && y->p.z >= lo.z &&
                        y->p.z < hi.z;
    box.add(inside ? 1.0 / y->pdf : 0.0);
  }
  const Vec3 e = hi - lo;
  EXPECT_NEAR(box.mean(), e.x * e.y * e.z, 4.0 * box.se()) << "se " << box.se();
  EXPECT_EQ(sampler.pdf({5.0f, 0.5f, 0.5f}), 0.0f);  // far outside
}

// The direction density seen from a point is a density over the sphere (integrates to 1), from
// outside the emitter and from inside it.
TEST(EmissionSampler, DirectionDensityIntegratesToOne) {
  const VolumeScene volumes({ramp_emitter()});
  VolumeContext context;
  const EmissionSampler sampler = EmissionSampler::build(volumes, context);
  for (const Vec3 x : {Vec3(1.2f, 1.2f, 4.0f), Vec3(0.9f, 1.1f, 1.3f)}) {
    Pcg32 rng(11, 2);
    Stat s;
    for (int i = 0; i < 100000; ++i) {
      const Vec3 w = sample_uniform_sphere({rng.next_float(), rng.next_float()});
      s.add(double(sampler.direction_pdf(x, w)) * 4.0 * kPi);
    }
    EXPECT_NEAR(s.mean(), 1.0, 4.0 * s.se()) << "from " << x.x << " " << x.y << " " << x.z << ", se " << s.se();
  }
}

// ... and it is the density of the sampled points' directions: E[g(w) / p(w)] over sampled
// points is the solid angle of a cone g inside what the emitter covers, 2 pi (1 - cos theta).
TEST(EmissionSampler, DirectionDensityIsTheDensityOfSampledDirections) {
  const VolumeScene volumes({ramp_emitter()});
  VolumeContext context;
  const EmissionSampler sampler = EmissionSampler::build(volumes, context);
  const Vec3 x(1.2f, 1.2f, 4.0f), axis = normalize(Vec3(1.2f, 1.2f, 1.2f) - x);
  const float cos_theta = std::cos(0.12f);
  Pcg32 rng(5, 9);
  Stat s;
  for (int i = 0; i < 40000; ++i) {
    const auto y = sampler.sample(rng.next_float(), {rng.next_float(), rng.next_float(), rng.next_float()});
    const Vec3 w = normalize(y->p - x);
    s.add(dot(w, axis) >= cos_theta ? 1.0 / sampler.direction_pdf(x, w) : 0.0);
  }
  EXPECT_NEAR(s.mean(), 2.0 * kPi * (1.0 - cos_theta), 4.0 * s.se()) << "se " << s.se();
}

// Emission at a point is what the march shades there: inside the grid, the shader's emission
// times the filtered density; outside every primitive, nothing.
TEST(EmissionSampler, EmissionAtAPointIsTheShadersEmission) {
  const VolumePrimitive emitter = ramp_emitter();
  const VolumeScene volumes({emitter});
  VolumeContext context;
  const Vec3 p(0.95f, 1.0f, 1.0f);
  const RGB e = emission_at(volumes, p, context);
  const RGB expected = shade_volume(emitter, p, context).emission;
  for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(e[c], expected[c]);
  EXPECT_GT(e.r, 0.0f);
  EXPECT_TRUE(emission_at(volumes, {-3.0f, 1.0f, 1.0f}, context).is_black());
}

int add_material(SceneDesc& desc, Bsdf bsdf) {
  desc.materials.push_back({std::to_string(desc.materials.size()), bsdf, {}, false});
  return int(desc.materials.size()) - 1;
}

// A small emitting, absorbing and scattering grid above a diffuse floor, beside a scattering
// fog sphere, in the dark, with the camera on the floor in front of them (neither in view):
// everything it sees is lit by the emitter alone, through surface vertices (the floor) and
// medium vertices (the fog and the emitter's own scattering).
SceneDesc flame_over_floor() {
  SceneDesc desc = testing::camera_at({1.2f, 3.0f, 5.0f}, {1.2f, 0.0f, 3.2f}, {16, 12}, 30.0f);
  const auto grid = make_grid([](int i, int j, int k) { return (i + j + k) % 3 == 0 ? 1.0f : 0.3f; }, 8, 0.1f,
                              Vec3(0.8f, 0.6f, 0.8f));
  VolumePrimitive flame = grid_primitive(grid, RGB(2.0f), RGB(1.0f));
  flame.shader.emission = RGB(20.0f, 8.0f, 2.0f);
  desc.volumes.push_back(flame);
  desc.volumes.push_back({SphereVolumeShape{Sphere::make({2.2f, 0.7f, 1.4f}, 0.5f, {})}, {RGB(0.1f), RGB(1.5f)}});
  desc.shapes.push_back({RectangleShape{{-2, 0, 4}, {6, 0, 0}, {0, 0, -6}}, {}, add_material(desc, DiffuseBsdf{RGB(0.7f)})});
  return desc;
}

// Means of 8 renders with and without the emission connections agree within 4 standard errors
// of the difference (no bias from the MIS split), and the connections lower the noise of the
// floor's pixels (their variance over the renders, averaged over the pixels) by more than 4x
// (measured: see the printout).
TEST(EmissionScenes, SampledEmissionKeepsTheMeanAndLowersTheNoise) {
  const SceneDesc desc = flame_over_floor();
  const auto scene = Scene::build(desc);
  ASSERT_FALSE(scene->emission_sampler().empty());
  const int runs = 8;
  Stat image_means[2];
  double pixel_variance[2] = {};
  for (int sampled = 0; sampled < 2; ++sampled) {
    std::vector<Stat> pixels(size_t(desc.camera.resolution.x * desc.camera.resolution.y));
    for (int run = 0; run < runs; ++run) {
      RenderSettings s = render_settings(desc);
      s.spp = 16;
      s.seed = uint64_t(run);
      s.path.limits = {.max_bounces = 8, .max_volume_bounces = 8};
      s.path.sample_emission = sampled == 1;
      const Image image = render(*scene, s).image;
      double sum = 0.0;
      for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
          const double v = image.rgb(x, y, 0).average();
          pixels[size_t(y * image.width() + x)].add(v);
          sum += v;
        }
      image_means[sampled].add(sum / double(pixels.size()));
    }
    for (const Stat& p : pixels) pixel_variance[sampled] += p.se() * p.se() * runs / double(pixels.size());
  }
  std::printf("flame over floor: image mean %.5f (bounce rays only) %.5f (sampled), pixel variance %.3g -> %.3g\n",
              image_means[0].mean(), image_means[1].mean(), pixel_variance[0], pixel_variance[1]);
  EXPECT_NEAR(image_means[1].mean(), image_means[0].mean(),
              4.0 * std::hypot(image_means[0].se(), image_means[1].se()));
  EXPECT_LT(pixel_variance[1], 0.25 * pixel_variance[0]);
}

// Emission connections and tracked segments draw from the sample alone (their own dimensions,
// generators seeded by Sampler::stream_key): the image is the same bit for bit for any thread
// count and tiling, and progressive passes end where one render of all the samples does (what a
// resumed checkpoint continues from, and what MPI ranks merge).
TEST(EmissionScenes, TrackedEmissiveImagesArePureFunctionsOfTheSample) {
  SceneDesc desc = flame_over_floor();
  desc.camera.look_at = {1.2f, 0.5f, 1.2f};  // the emitter in view as well
  const auto scene = Scene::build(desc);
  RenderSettings s = render_settings(desc);
  s.spp = 6;
  s.path.secondary = SecondarySegments::kTrack;
  s.threads = 1;
  Film whole(s.resolution, s.aovs);
  render_into(whole, *scene, s);
  s.threads = 2;
  s.tile_size = 5;
  Film tiled(s.resolution, s.aovs);
  render_into(tiled, *scene, s);
  EXPECT_TRUE(tiled == whole);
  Film passes(s.resolution, s.aovs);
  render_up_to(passes, *scene, s, 2);
  render_up_to(passes, *scene, s, 6);
  EXPECT_TRUE(passes == whole);
}

}  // namespace
}  // namespace caligo
