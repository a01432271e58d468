// Guided distance sampling (guided_distance.h) on a field whose fluence is ten times higher in
// the half x >= 1/2: the mixture's pdf integrates to one over the record, the samples follow it
// (histogram against the pdf's integral per bin), the pdf a sample reports is the pdf at its
// distance, and the bright half draws more of them than the record's own density would.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/rng.h"
#include "guiding/directional_tree.h"
#include "integrators/guided_distance.h"

namespace caligo {
namespace {

// Two iterations: the first splits the root along x (its vertices pass the threshold), the
// second teaches each half its own fluence (4 pi x the recorded radiance).
GuidingField two_level_field() {
  GuidingField field({Vec3(0.0f), Vec3(1.0f)}, {.spatial_threshold = 100});
  for (int iteration = 0; iteration < 2; ++iteration) {
    for (int i = 0; i < 4000; ++i) {
      Pcg32 rng{uint64_t(i), uint64_t(iteration)};
      const Vec3 x{rng.next_float(), rng.next_float(), rng.next_float()};
      const Vec3 w = square_to_sphere({rng.next_float(), rng.next_float()});
      const double radiance = x.x >= 0.5f ? 10.0 : 1.0;
      field.record(x, GuidingRecord{w, radiance, 1.0f, 1.0f / (4.0f * kPi), 1.0f / (4.0f * kPi), false});
    }
    field.finish_iteration();
  }
  return field;
}

TEST(GuidedDistance, ThePdfIntegratesToOneAndMatchesItsSamples) {
  const GuidingField field = two_level_field();
  Bounds3 leaf;
  ASSERT_NEAR(field.fluence({0.75f, 0.5f, 0.5f}, &leaf) / field.fluence({0.25f, 0.5f, 0.5f}, &leaf), 10.0f, 0.5f);
  // A grey record along x through the unit cube, in two steps of different density.
  TransmittanceRecord record;
  const PhaseLobe lobe{RGB(1.0f), {}};
  record.push(0.05f, 0.6f, RGB(2.0f), RGB(1.5f), {&lobe, 1});
  record.push(0.6f, 0.95f, RGB(4.0f), RGB(3.0f), {&lobe, 1});
  const Ray ray{{0.0f, 0.5f, 0.5f}, {1.0f, 0.0f, 0.0f}, 0.0f, 1.0f};
  const auto guided = GuidedDistance::along(field, ray, record);
  ASSERT_TRUE(guided.has_value());

  constexpr int kBins = 30, kSteps = 30000;
  std::vector<double> mass(kBins, 0.0);  // the pdf's integral per bin (midpoint rule)
  double integral = 0.0, bright = 0.0, bright_native = 0.0;
  for (int i = 0; i < kSteps; ++i) {
    const float t = 0.05f + 0.9f * (float(i) + 0.5f) / kSteps;
    const double p = guided->pdf(record, t) * 0.9 / kSteps;
    integral += p;
    mass[size_t(std::min(int((t - 0.05f) / 0.9f * kBins), kBins - 1))] += p;
    if (t >= 0.5f) {
      bright += p;
      bright_native += record.scatter_density_pdf(t) * 0.9 / kSteps;
    }
  }
  EXPECT_NEAR(integral, 1.0, 1e-3);
  EXPECT_GT(bright, bright_native + 0.1);  // the bright half draws more than the record alone would

  constexpr int kSamples = 200000;
  std::vector<double> histogram(kBins, 0.0);
  for (int i = 0; i < kSamples; ++i) {
    float native = 0.0f;
    const auto s = guided->sample(record, (float(i) + 0.5f) / kSamples, &native);
    ASSERT_TRUE(s.has_value());
    ASSERT_NEAR(s->pdf, guided->pdf(record, s->t), 1e-4f * s->pdf);
    ASSERT_NEAR(native, record.scatter_density_pdf(s->t), 1e-4f * native);
    histogram[size_t(std::min(int((s->t - 0.05f) / 0.9f * kBins), kBins - 1))] += 1.0 / kSamples;
  }
  // Stratified numbers: the error per bin is of order a bin edge's share, far below 1e-3.
  for (int b = 0; b < kBins; ++b) EXPECT_NEAR(histogram[size_t(b)], mass[size_t(b)], 1e-3) << "bin " << b;
}

// Without fluence anywhere along the ray (a field never trained), distances are not guided.
TEST(GuidedDistance, AnUntrainedFieldGuidesNothing) {
  const GuidingField field({Vec3(0.0f), Vec3(1.0f)}, {});
  TransmittanceRecord record;
  const PhaseLobe lobe{RGB(1.0f), {}};
  record.push(0.0f, 1.0f, RGB(1.0f), RGB(1.0f), {&lobe, 1});
  EXPECT_FALSE(GuidedDistance::along(field, {{0.0f, 0.5f, 0.5f}, {1.0f, 0.0f, 0.0f}, 0.0f, 1.0f}, record));
}

}  // namespace
}  // namespace caligo
