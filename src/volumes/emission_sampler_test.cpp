// The emission sampler over an analytic emitter (a glowing sphere, its lattice the bounds'
// 4^3 cells): sampled points against their density, and the direction density as a density
// over the sphere of directions. The grid lattice is tested with grids in
// integrators/emission_scenes_test.cpp. Tolerances: 4 standard errors of the estimate's sample.
#include "volumes/emission_sampler.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/math.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "core/test_stat.h"

namespace caligo {
namespace {

using testing::Stat;

VolumeScene glowing_sphere() {
  VolumePrimitive v{SphereVolumeShape{Sphere::make({1.0f, 2.0f, -1.0f}, 0.8f, {})}, {RGB(1.0f), RGB(0.5f)}};
  v.shader.emission = RGB(3.0f, 2.0f, 1.0f);
  VolumePrimitive dark{SphereVolumeShape{Sphere::make({-2.0f, 0.0f, 0.0f}, 0.5f, {})}, {RGB(1.0f), RGB(0.5f)}};
  return VolumeScene({v, dark});
}

// E[g(y) / pdf(y)] over sampled points is the volume of g's support (here the emitting sphere:
// the proposal covers its bounds, so points outside it count 0), and no point lands elsewhere.
TEST(EmissionSampler, PointsInAnAnalyticEmitterFollowTheirDensity) {
  const VolumeScene volumes = glowing_sphere();
  VolumeContext context;
  const EmissionSampler sampler = EmissionSampler::build(volumes, context);
  ASSERT_FALSE(sampler.empty());
  EXPECT_EQ(sampler.cells(), 64u);
  Pcg32 rng(1, 2);
  Stat volume;
  for (int i = 0; i < 40000; ++i) {
    const auto y = sampler.sample(rng.next_float(), {rng.next_float(), rng.next_float(), rng.next_float()});
    ASSERT_TRUE(y.has_value());
    ASSERT_FLOAT_EQ(y->pdf, sampler.pdf(y->p));
    volume.add(length(y->p - Vec3(1.0f, 2.0f, -1.0f)) < 0.8f ? 1.0 / y->pdf : 0.0);
  }
  EXPECT_NEAR(volume.mean(), 4.0 / 3.0 * kPi * 0.8 * 0.8 * 0.8, 4.0 * volume.se()) << "se " << volume.se();
  EXPECT_EQ(sampler.pdf({-2.0f, 0.0f, 0.0f}), 0.0f);  // the dark sphere is not a proposal
}

TEST(EmissionSampler, DirectionDensityOfAnAnalyticEmitterIntegratesToOne) {
  const VolumeScene volumes = glowing_sphere();
  VolumeContext context;
  const EmissionSampler sampler = EmissionSampler::build(volumes, context);
  for (const Vec3 x : {Vec3(0.0f, 0.0f, 3.0f), Vec3(1.1f, 2.1f, -0.9f)}) {
    Pcg32 rng(4, 4);
    Stat s;
    for (int i = 0; i < 100000; ++i) s.add(double(sampler.direction_pdf(x, sample_uniform_sphere({rng.next_float(), rng.next_float()}))) * 4.0 * kPi);
    EXPECT_NEAR(s.mean(), 1.0, 4.0 * s.se()) << "se " << s.se();
  }
}

TEST(EmissionSampler, NothingEmitsNothingToSample) {
  VolumeContext context;
  const VolumeScene volumes({{SphereVolumeShape{Sphere::make({0, 0, 0}, 1.0f, {})}, {RGB(1.0f), RGB(1.0f)}}});
  EXPECT_TRUE(EmissionSampler::build(volumes, context).empty());
  EXPECT_FALSE(EmissionSampler().sample(0.5f, Vec3(0.5f)).has_value());
  EXPECT_EQ(EmissionSampler().direction_pdf(Vec3(0.0f), Vec3(0, 0, 1)), 0.0f);
}

}  // namespace
}  // namespace caligo
