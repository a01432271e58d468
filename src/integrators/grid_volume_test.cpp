// Sparse-grid volumes through the whole spine: majorant intervals, marching with constant
// blocks in one step, the reference ladder's delta tracking with interval majorants.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include <nanovdb/util/GridBuilder.h>

#include "grids/volume_grid_build.h"
#include "integrators/test_grids.h"
#include "core/rng.h"
#include "integrators/reference.h"
#include "media/blackbody.h"
#include "raymarch/march.h"
#include "tracking/tracking.h"
#include "render/render.h"

namespace caligo {
namespace {

using testing::grid_primitive;
using testing::make_grid;


// A 32^3 block of density 0.5 (voxel 0.1 m): along a line through its middle the trilinear
// field ramps up over one voxel, is flat for 31 and ramps down over one, so the optical depth
// is sigma_t * 0.1 * (0.5 * 31 + 2 * 0.25) = sigma_t * 1.6 (nearest: 0.5 over 32 voxels, the
// same). The marcher takes the constant blocks in one step each and must reproduce it.
TEST(GridVolume, TransmittanceThroughAConstantGridIsAnalytic) {
  const auto grid = make_grid([](int, int, int) { return 0.5f; }, 32, 0.1f, Vec3(0.0f));
  const RGB sigma_a(0.4f, 0.8f, 1.2f), sigma_s(0.6f);
  for (const GridFilter filter : {GridFilter::kTrilinear, GridFilter::kNearest}) {
    const VolumeScene volumes({grid_primitive(grid, sigma_a, sigma_s, filter)});
    const Ray ray{{-1.0f, 1.55f, 1.45f}, {1, 0, 0}, 0.0f, kInfinity};
    MarchScratch scratch;
    // The ramps are marched with a jitter: their optical depth is exact in the mean over it.
    double depth = 0;
    const int jitters = 64;
    for (int j = 0; j < jitters; ++j)
      depth -= std::log(march_transmittance(volumes, ray, (float(j) + 0.5f) / jitters, {}, scratch).g);
    EXPECT_NEAR(depth / jitters, 1.4 * 1.6, 1e-3) << "filter " << int(filter);
    // The three constant blocks in the middle are one step: the record has the 8 + 8 voxel
    // steps of the two end blocks (the footprint of the first reaches into the empty block
    // before it) and one more, not a step per voxel crossed (34).
    TransmittanceRecord record;
    march(volumes, ray, 0.5f, {}, scratch, record);
    EXPECT_LE(record.steps().size(), 17u);
    // The record and the shadow-ray transmittance march the same steps.
    EXPECT_NEAR(record.transmittance_end().b, march_transmittance(volumes, ray, 0.5f, {}, scratch).b, 1e-6f);
  }
}

// Ratio tracking on the same grid takes each interval's majorant from the block structure: its
// mean is the same Beer-Lambert answer, within 4 standard errors of 20,000 rays.
TEST(GridVolume, RatioTrackingThroughAConstantGridIsAnalytic) {
  const auto grid = make_grid([](int, int, int) { return 0.5f; }, 32, 0.1f, Vec3(0.0f));
  const VolumeScene volumes({grid_primitive(grid, RGB(0.4f, 0.8f, 1.2f), RGB(0.6f))});
  const Ray ray{{-1.0f, 1.55f, 1.45f}, {1, 0, 0}, 0.0f, kInfinity};
  MarchScratch scratch;
  Pcg32 rng(5, 7);
  double sum = 0, sum2 = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const double t = track_transmittance(volumes, ray, {}, scratch, rng).g;
    sum += t;
    sum2 += t * t;
  }
  const double mean = sum / n, se = std::sqrt((sum2 / n - mean * mean) / n);
  EXPECT_NEAR(mean, std::exp(-1.4 * 1.6), 4.0 * se);
}

// Residual ratio tracking (the blocks' minima as the control) and plain ratio tracking estimate
// the same transmittance through a heterogeneous grid, within 4 standard errors of each other and
// of a fine march (jitter-averaged; the march's own step error, ~1e-4, is added to the
// tolerance); the residual one with fewer lookups and less variance, as the control takes the
// part of the optical depth every block shares out of the estimate.
TEST(GridVolume, ResidualRatioTrackingMatchesRatioTrackingWithFewerLookups) {
  const auto grid = make_grid(
      [](int i, int j, int k) { return 1.0f + 0.4f * std::sin(0.5f * float(i)) * std::cos(0.3f * float(j + k)); }, 32,
      0.1f, Vec3(0.0f));
  const VolumeScene volumes({grid_primitive(grid, RGB(0.3f, 0.6f, 0.9f), RGB(0.5f))});
  const Ray ray{{-1.0f, 1.15f, 1.75f}, normalize(Vec3(1.0f, 0.2f, -0.1f)), 0.0f, kInfinity};
  MarchScratch scratch;
  double marched = 0;
  const int jitters = 32;
  for (int j = 0; j < jitters; ++j)
    marched += march_transmittance(volumes, ray, (float(j) + 0.5f) / jitters, {}, scratch).b / jitters;
  double mean[2], se[2];
  uint64_t lookups[2];
  for (int residual = 0; residual < 2; ++residual) {
    Pcg32 rng(9, 4);
    scratch.shader_evaluations = 0;
    double sum = 0, sum2 = 0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
      const double t = track_transmittance(volumes, ray, {}, scratch, rng, -1, residual == 1).b;
      sum += t;
      sum2 += t * t;
    }
    mean[residual] = sum / n;
    se[residual] = std::sqrt(std::max(0.0, sum2 / n - mean[residual] * mean[residual]) / n);
    lookups[residual] = scratch.shader_evaluations;
    EXPECT_NEAR(mean[residual], marched, 4.0 * se[residual] + 1e-4) << "residual " << residual;
  }
  std::printf("transmittance %.5f: ratio %.5f +- %.5f (%llu lookups), residual %.5f +- %.5f (%llu lookups)\n",
              marched, mean[0], se[0], (unsigned long long)lookups[0], mean[1], se[1],
              (unsigned long long)lookups[1]);
  EXPECT_NEAR(mean[1], mean[0], 4.0 * std::hypot(se[0], se[1]));
  // Measured: 0.71x the lookups and 0.40x the standard error.
  EXPECT_LT(double(lookups[1]), 0.8 * double(lookups[0]));
  EXPECT_LT(se[1], 0.6 * se[0]);
}

// The reference ladder's transmittance uses the intervals too: exact for the same grid
// (midpoint steps over each interval; the trilinear ramps are linear, so midpoints are exact
// once the steps are aligned with the ramp, which the interval ends ensure).
TEST(GridVolume, ReferenceTransmittanceThroughAConstantGrid) {
  const auto grid = make_grid([](int, int, int) { return 0.5f; }, 32, 0.1f, Vec3(0.0f));
  SceneDesc desc;
  desc.file = "test";
  desc.camera = {{0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 40.0f, {4, 4}};
  desc.volumes.push_back(grid_primitive(grid, RGB(0.4f), RGB(0.6f), GridFilter::kNearest));
  const auto scene = Scene::build(desc);
  const RGB t = reference_transmittance(*scene, Ray{{-1.0f, 1.55f, 1.45f}, {1, 0, 0}}, kInfinity, 64);
  EXPECT_NEAR(-std::log(t.r), 1.6, 1e-3);
}

// A grid's other channels: Cd (clamped to [0, 1]) tints sigma_s, temperature emits as a
// blackbody, flame as colour x intensity; the interval's majorant still bounds sigma_t.
TEST(GridVolume, ShadingReadsColorTemperatureAndFlame) {
  const auto constant = [](float v) {
    nanovdb::GridBuilder<float> b(0.0f);
    b([&](const nanovdb::Coord&) { return v; }, nanovdb::CoordBBox(nanovdb::Coord(0), nanovdb::Coord(15)));
    return b.getHandle<>(0.1, nanovdb::Vec3d(0.0), "g");
  };
  nanovdb::GridBuilder<nanovdb::Vec3f> cd(nanovdb::Vec3f(0.0f));
  cd([](const nanovdb::Coord&) { return nanovdb::Vec3f(0.2f, 0.5f, 1.5f); },
     nanovdb::CoordBBox(nanovdb::Coord(0), nanovdb::Coord(15)));
  NanoGrids grids{constant(0.5f), constant(1500.0f), constant(0.25f), cd.getHandle<>(0.1, nanovdb::Vec3d(0.0), "Cd")};
  const auto grid = make_volume_grid(std::move(grids), {"test", ""});
  ASSERT_TRUE(grid->has_color() && grid->has_temperature() && grid->has_flame());
  VolumePrimitive prim = grid_primitive(grid, RGB(0.3f), RGB(2.0f));
  prim.shader.density = 4.0f;
  prim.shader.blackbody = BlackbodyEmission{2e-6f, 1.0f, 0.0f};
  prim.shader.flame = FlameEmission{RGB(1.0f, 0.4f, 0.1f), 3.0f};
  VolumeContext ctx;
  const Vec3 centre(0.75f, 0.75f, 0.75f);
  const MediumSample m = shade_volume(prim, centre, ctx);
  EXPECT_NEAR(m.sigma_a.g, 0.3f * 4.0f * 0.5f, 1e-5f);
  EXPECT_NEAR(m.sigma_s.r, 2.0f * 2.0f * 0.2f, 1e-5f);
  EXPECT_NEAR(m.sigma_s.g, 2.0f * 2.0f * 0.5f, 1e-5f);
  EXPECT_NEAR(m.sigma_s.b, 2.0f * 2.0f * 1.0f, 1e-5f);  // 1.5 clamped to 1
  const RGB expected = blackbody_color(1500.0f) * (2e-6f * blackbody_exitance_radiance(1500.0f)) +
                       RGB(1.0f, 0.4f, 0.1f) * (3.0f * 0.25f);
  EXPECT_NEAR(m.emission.r, expected.r, 1e-4f * expected.r);
  EXPECT_NEAR(m.emission.b, expected.b, 1e-4f * expected.r);
  // An absurd temperature scale is clamped (10^6 K), not turned into infinite emission.
  prim.shader.blackbody->temperature_scale = 1e30f;
  EXPECT_TRUE(shade_volume(prim, centre, ctx).emission.is_finite());
  prim.shader.blackbody->temperature_scale = 1.0f;
  // Without the tint, sigma_s is grey again.
  prim.shader.tint_with_color_grid = false;
  EXPECT_NEAR(shade_volume(prim, centre, ctx).sigma_s.r, 4.0f, 1e-5f);
  // The interval through the centre bounds sigma_t and is constant inside (all channels equal there).
  append_intervals(prim, 0, Ray{{-1, 0.75f, 0.75f}, {1, 0, 0}}, ctx);
  ASSERT_FALSE(ctx.intervals.empty());
  for (const VolumeInterval& iv : ctx.intervals) EXPECT_GE(iv.sigma_maj.g + 1e-5f, m.sigma_t().g);
}

// The bias of larger steps (docs/techniques.md): a jittered step samples the field once per
// step, so the optical depth is right on average over the jitter but transmittance, its
// exponential, is not (Jensen: E[exp(-tau)] >= exp(-E[tau])), and the gap grows with the
// variance of the estimate, i.e. with the step. Measured on a grid whose density changes
// from voxel to voxel: transmittance averaged over 256 jitters against the ladder's fine
// quadrature, for step_scale 1, 2, 4, 8.
TEST(GridVolume, LargerStepsBiasTransmittanceUpwards) {
  const auto grid = make_grid(
      [](int i, int j, int k) {
        // Independent values per voxel (a hash), so no step size aliases with the pattern.
        const uint64_t h = hash_values(uint64_t(i), uint64_t(j), uint64_t(k));
        return 0.05f + 0.9f * float(h >> 40) / float(1ull << 24);
      },
      48, 0.05f, Vec3(0.0f));
  VolumePrimitive prim = grid_primitive(grid, RGB(0.5f), RGB(1.5f));
  SceneDesc desc;
  desc.file = "test";
  desc.camera = {{0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 40.0f, {4, 4}};
  desc.volumes.push_back(prim);
  const Ray ray{{-0.5f, 1.13f, 1.21f}, normalize(Vec3(1.0f, 0.05f, -0.03f)), 0.0f, kInfinity};
  const auto scene = Scene::build(desc);
  const double exact = reference_transmittance(*scene, ray, kInfinity, 4096).g;
  ASSERT_GT(exact, 1e-3);
  std::vector<double> bias;
  for (const float scale : {1.0f, 2.0f, 4.0f, 8.0f}) {
    prim.shader.step_scale = scale;
    const VolumeScene volumes({prim});
    MarchScratch scratch;
    double mean = 0;
    const int jitters = 256;
    for (int j = 0; j < jitters; ++j)
      mean += march_transmittance(volumes, ray, (float(j) + 0.5f) / jitters, {}, scratch).g;
    bias.push_back(mean / jitters / exact - 1.0);
  }
  // One voxel per step: within 1 % of the exact transmittance; the bias is upwards and grows
  // with the step.
  EXPECT_LT(std::abs(bias[0]), 0.01) << bias[0];
  for (size_t i = 1; i < bias.size(); ++i) {
    EXPECT_GT(bias[i], bias[i - 1]) << "step_scale " << (1 << i);
    EXPECT_GT(bias[i], 0.0);
  }
  std::printf("step_scale 1, 2, 4, 8: transmittance bias %+.4f %+.4f %+.4f %+.4f (T = %.4f)\n", bias[0], bias[1],
              bias[2], bias[3], exact);
}

// A cloud-like grid rendered by the production path tracer (decoupled marching, one voxel
// steps, equiangular + density MIS) and by the ladder's delta tracking with the intervals'
// majorants: all orders of scattering, both unbiased up to the march's jitter-averaged
// quadrature, so their image means agree within the 1 %. Standard deviations of the
// two means over seeds, measured at these sample counts: 0.07 % (production) and 0.19 %
// (delta tracking) of the mean, so a 1 % difference is a bias, not noise.
TEST(GridVolume, ProductionMarcherAgreesWithDeltaTrackingOnAGridCloud) {
  const int n = 24;
  const auto cloud = make_grid(
      [&](int i, int j, int k) {
        const float x = (float(i) - 11.5f) / 10.0f, y = (float(j) - 11.5f) / 8.0f, z = (float(k) - 11.5f) / 10.0f;
        const float r2 = x * x + y * y + z * z;
        // A lumpy ball: density from 0 to 1 with a ripple, exactly zero outside.
        if (r2 >= 1.0f) return 0.0f;
        return (1.0f - r2) * (0.75f + 0.25f * std::sin(3.0f * float(i)) * std::cos(2.0f * float(k)));
      },
      n, 0.1f, Vec3(-1.15f, -1.15f, -1.15f));
  SceneDesc desc;
  desc.file = "test";
  desc.camera = {{0, 0.3f, 5}, {0, 0, 0}, {0, 1, 0}, 30.0f, {8, 8}};
  desc.render.path.limits.max_bounces = 16;
  desc.volumes.push_back(grid_primitive(cloud, RGB(0.4f), RGB(3.6f)));
  desc.volumes.back().shader.phase = HenyeyGreensteinPhase{0.5f};
  desc.lights.push_back(DirectionalLight{normalize(Vec3(-0.5f, -0.7f, -0.4f)), RGB(3.0f)});
  desc.lights.push_back(EnvironmentLight{RGB(0.2f, 0.3f, 0.5f)});
  const auto scene = Scene::build(desc);

  RenderSettings s = render_settings(desc);
  s.spp = 2048;
  s.path.limits = {.max_bounces = 16, .max_volume_bounces = 16};
  s.path.secondary = SecondarySegments::kMarch;
  const Image production = render(*scene, s).image;
  double produced = 0;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) produced += production.rgb(x, y, 0).average();
  produced /= 64.0;

  ReferenceOptions options;
  options.samples_per_pixel = 2048;
  options.limits = {.max_bounces = 16, .max_volume_bounces = 16};
  options.seed = 11;
  const RGB reference = reference_mean_radiance(*scene, {8, 8}, options);
  EXPECT_GT(reference.average(), 0.05f);
  EXPECT_NEAR(produced, reference.average(), 0.01 * reference.average());
  // Every segment after the camera's tracked (spectral and ratio tracking): the same answer.
  s.path.secondary = SecondarySegments::kTrack;
  const Image tracked = render(*scene, s).image;
  double tracked_mean = 0;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) tracked_mean += tracked.rgb(x, y, 0).average();
  tracked_mean /= 64.0;
  std::printf("grid cloud: march %.5f, track %.5f, delta-tracking reference %.5f\n", produced, tracked_mean,
              reference.average());
  EXPECT_NEAR(tracked_mean, reference.average(), 0.01 * reference.average());
}

}  // namespace
}  // namespace caligo
