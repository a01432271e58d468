// SegmentMediaBatch (media_simd.h) against media.h's scalar segment_optical_depth: random
// segments through every primitive kind, with and without the per-tile classification.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "realtime/media.h"
#include "realtime/media_simd.h"

namespace caligo {
namespace {

using B = xsimd::batch<float>;
constexpr size_t kLanes = B::size;

VolumeShader medium(float sigma_t) {
  VolumeShader s;
  s.sigma_a = RGB(0.2f, 0.4f, 0.6f) * sigma_t;
  s.sigma_s = RGB(0.8f, 0.6f, 0.4f) * sigma_t;
  return s;
}

VolumeScene test_volumes() {
  std::vector<VolumePrimitive> prims;
  prims.push_back({BoxVolumeShape{{}, {-6, -1, -6}, {6, 5, 6}}, medium(0.05f)});
  prims.push_back(
      {BoxVolumeShape{Transform::translate({1.0f, 1.0f, -0.5f}) * Transform::rotate(0.6f, {1, 1, 0}) *
                          Transform::scale({1.0f, 0.5f, 2.0f}),
                      {-1, -1, -1},
                      {1, 1, 1}},
       medium(0.7f)});
  VolumeShader noisy = medium(0.4f);
  noisy.noise = NoiseModulation{1.5f, 0.8f, {0.3f, 0.1f, 0.0f}, {}};
  noisy.density = 1.7f;
  prims.push_back(
      {SphereVolumeShape{Sphere::make({-1.5f, 1.0f, 0.5f}, 1.2f, Transform::scale({1.0f, 0.7f, 1.4f}))},
       noisy});
  VolumeShader puff = medium(2.0f);
  puff.field = RadialFalloffDensity{2.0f};
  prims.push_back({SphereVolumeShape{Sphere::make({0.5f, 2.0f, 1.5f}, 1.0f, {})}, puff});
  return VolumeScene(std::move(prims));
}

struct Segments {
  alignas(32) float a[3][kLanes], b[3][kLanes];
  Vec3 at(const float (&v)[3][kLanes], size_t i) const { return {v[0][i], v[1][i], v[2][i]}; }
};

void expect_matches(const SegmentMediaBatch& batch, const VolumeScene& volumes, const Segments& s,
                    const SegmentMediaBatch::Overlap* overlaps) {
  B r, g, b;
  const auto load = [](const float* p) { return B::load_aligned(p); };
  batch.transmittance(load(s.a[0]), load(s.a[1]), load(s.a[2]), load(s.b[0]), load(s.b[1]), load(s.b[2]),
                      B(0.0f) == B(0.0f), overlaps, r, g, b);
  for (size_t i = 0; i < kLanes; ++i) {
    const RGB tau = segment_optical_depth(volumes, s.at(s.a, i), s.at(s.b, i));
    const RGB expected{std::exp(-tau.r), std::exp(-tau.g), std::exp(-tau.b)};
    ASSERT_NEAR(r.get(i), expected.r, 2e-5f + 1e-4f * expected.r) << i;
    ASSERT_NEAR(g.get(i), expected.g, 2e-5f + 1e-4f * expected.g) << i;
    ASSERT_NEAR(b.get(i), expected.b, 2e-5f + 1e-4f * expected.b) << i;
  }
}

// Segments anywhere (starting and ending inside, outside or on either side of each
// primitive), tested against every primitive.
TEST(SegmentMediaBatch, MatchesScalarOpticalDepth) {
  const VolumeScene volumes = test_volumes();
  const SegmentMediaBatch batch(volumes);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-4.0f, 4.0f);
  int attenuated = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    Segments s;
    for (size_t i = 0; i < kLanes; ++i)
      for (int k = 0; k < 3; ++k) s.a[k][i] = u(rng), s.b[k][i] = u(rng);
    if (trial % 7 == 0)  // zero-length segments
      for (int k = 0; k < 3; ++k) s.b[k][3] = s.a[k][3];
    expect_matches(batch, volumes, s, nullptr);
    attenuated += segment_optical_depth(volumes, s.at(s.a, 0), s.at(s.b, 0)).r > 0.5f;
  }
  EXPECT_GT(attenuated, 100);  // the dense primitives are crossed often
}

// Segments from one small box to another: classify's answer must leave the result as it is
// without it, and be the obvious one where the boxes are far inside or far from a primitive.
TEST(SegmentMediaBatch, ClassifiedFamiliesMatchUnclassified) {
  const VolumeScene volumes = test_volumes();
  const SegmentMediaBatch batch(volumes);
  ASSERT_EQ(batch.size(), 4u);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> centre(-9.0f, 9.0f), size(0.0f, 1.5f), t(0.0f, 1.0f);
  int whole = 0, none = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    Bounds3 from, to;
    for (Bounds3* box : {&from, &to}) {
      const Vec3 c{centre(rng), centre(rng) * 0.5f + 2.0f, centre(rng)};
      const Vec3 h{size(rng), size(rng), size(rng)};
      box->lo = c - h;
      box->hi = c + h;
    }
    SegmentMediaBatch::Overlap overlaps[4];
    batch.classify(from, to, overlaps);
    for (SegmentMediaBatch::Overlap o : overlaps)
      whole += o == SegmentMediaBatch::Overlap::whole, none += o == SegmentMediaBatch::Overlap::none;
    Segments s;
    for (size_t i = 0; i < kLanes; ++i)
      for (int k = 0; k < 3; ++k) {
        s.a[k][i] = from.lo[k] + (from.hi[k] - from.lo[k]) * t(rng);
        s.b[k][i] = to.lo[k] + (to.hi[k] - to.lo[k]) * t(rng);
      }
    expect_matches(batch, volumes, s, overlaps);
  }
  EXPECT_GT(whole, 30);
  EXPECT_GT(none, 1000);
  // Analytic cases: both ends deep inside the fog box only; both far outside everything.
  SegmentMediaBatch::Overlap o[4];
  batch.classify({{4.5f, 0.0f, 4.5f}, {5.0f, 0.5f, 5.0f}}, {{4.0f, 3.0f, -5.0f}, {4.5f, 4.0f, -4.5f}}, o);
  EXPECT_EQ(o[0], SegmentMediaBatch::Overlap::whole);
  EXPECT_EQ(o[1], SegmentMediaBatch::Overlap::none);
  batch.classify({{20, 20, 20}, {21, 21, 21}}, {{30, 20, 20}, {31, 21, 21}}, o);
  for (SegmentMediaBatch::Overlap x : o) EXPECT_EQ(x, SegmentMediaBatch::Overlap::none);
}

}  // namespace
}  // namespace caligo
