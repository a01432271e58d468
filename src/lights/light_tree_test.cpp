// Tests of the light tree and the light-sampler seam (light_tree.h, light_sampler.h): for
// surface points (with and without a normal) and for ray segments, the frequency with which
// sample() chooses each light matches the pmf it reports (chi-squared over the lights plus a
// "nothing chosen" bin), every sample's pmf equals pmf() for that light bit for bit, pmfs sum
// to one, and pmf() > 0 for every light that can light the receiver (found by sampling points
// on it), so the tree never leaves out light and MIS can weight any hit.
#include "lights/light_sampler.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/rng.h"
#include "core/testing/chi_squared.h"
#include "lights/light_sample.h"

namespace caligo {
namespace {

constexpr double kMinPValue = 1e-4;  // per test; 9 queries x 2 kinds stay well clear of flukes
constexpr int kSamples = 100000;

Vec3 random_unit(Pcg32& rng) {
  for (;;) {
    const Vec3 v(2 * rng.next_float() - 1, 2 * rng.next_float() - 1, 2 * rng.next_float() - 1);
    if (length_squared(v) > 1e-3f && length_squared(v) <= 1.0f) return normalize(v);
  }
}

Vec3 random_point(Pcg32& rng, float half) {
  return {half * (2 * rng.next_float() - 1), half * (2 * rng.next_float() - 1), half * (2 * rng.next_float() - 1)};
}

// One of each finite type, many points and spots, a zero-power light, and two lights at infinity.
std::vector<Light> mixed_lights() {
  Pcg32 rng(7, 3);
  std::vector<Light> lights;
  for (int i = 0; i < 16; ++i)
    lights.push_back(PointLight{random_point(rng, 5), RGB(0.5f + 4 * rng.next_float())});
  for (int i = 0; i < 12; ++i) {
    SpotLight s{random_point(rng, 5), random_unit(rng)};
    const float outer = radians(15 + 70 * rng.next_float());
    s.cos_outer = std::cos(outer);
    s.cos_inner = std::cos(0.7f * outer);
    s.intensity = RGB(1 + 5 * rng.next_float());
    lights.push_back(s);
  }
  lights.push_back(SpotLight{{0, 2, 0}, {0, -1, 0}, std::cos(radians(100)), std::cos(radians(120)), RGB(2)});
  for (int i = 0; i < 5; ++i) {
    const Vec3 c = random_point(rng, 5);
    lights.push_back(QuadLight{c, random_unit(rng) * 0.8f, random_unit(rng) * 0.6f, RGB(3), i == 0});
    lights.push_back(TriangleLight{c + Vec3(0, 1, 0), c + random_unit(rng), c + random_unit(rng) * 0.7f, RGB(4), i == 1});
  }
  lights.push_back(SphereLight{{1, -1, 2}, 0.5f, RGB(2)});
  lights.push_back(SphereLight{{-3, 3, -1}, 0.2f, RGB(6), true});
  lights.push_back(BoxLight{{0, 4, 0}, {0, -1, 0}, {0, 0, 1}, 1.5f, 1.0f, 8.0f, RGB(1.5f)});
  lights.push_back(PointLight{{0, 0, 0}, RGB(0.0f)});  // no power: never chosen
  lights.push_back(DirectionalLight{normalize(Vec3(0.3f, -1, 0.2f)), RGB(1.0f), 1.0f, 10.0f});
  lights.push_back(EnvironmentLight{RGB(0.05f), 10.0f});
  return lights;
}

struct PointQuery {
  Vec3 p, n;
};

std::vector<PointQuery> point_queries() {
  return {{{0, -3, 0}, {0, 1, 0}},          {{4, 1, -2}, normalize(Vec3(-1, 0.2f, 0.3f))},
          {{-2, 0.5f, 3}, {0, 0, -1}},      {{0.5f, 0.2f, 0.1f}, {}},
          {{9, 9, 9}, normalize(Vec3(-1, -1, -1))}};
}

std::vector<Ray> segment_queries() {
  return {Ray{{-8, 0, 0}, {1, 0, 0}, 0.5f, 16.0f}, Ray{{0, -6, 1}, normalize(Vec3(0.2f, 1, -0.1f)), 1.0f, 12.0f},
          Ray{{3, 3, 3}, normalize(Vec3(-1, -0.5f, -1)), 0.0f, kInfinity},
          Ray{{0.5f, 0.5f, 0.5f}, {0, 0, 1}, 0.0f, 0.3f}};
}

// Chooses kSamples lights; checks each pmf against pmf(), then the counts against the pmfs.
template <class Sample, class Pmf>
void check_sampling(size_t light_count, const Sample& sample, const Pmf& pmf, const char* what) {
  std::vector<double> observed(light_count + 1, 0.0), expected(light_count + 1, 0.0);
  double total = 0.0;
  for (size_t i = 0; i < light_count; ++i) {
    expected[i] = kSamples * double(pmf(int(i)));
    total += double(pmf(int(i)));
  }
  EXPECT_LE(total, 1.0 + 1e-5) << what;
  expected[light_count] = std::max(0.0, kSamples * (1.0 - total));
  Pcg32 rng(11, 5);
  int mismatches = 0;
  for (int s = 0; s < kSamples; ++s) {
    const LightChoice c = sample(rng.next_float());
    if (c.light < 0) {
      observed[light_count] += 1;
      continue;
    }
    observed[size_t(c.light)] += 1;
    if (c.pmf != pmf(c.light)) ++mismatches;
  }
  EXPECT_EQ(mismatches, 0) << what;
  EXPECT_GT(test_stats::chi2_p_value(observed, expected), kMinPValue) << what;
}

// Both tree rules for lights at infinity: weighed at the receiver (the default) and the former
// fixed share.
TEST(LightTree, SurfacePointsChooseLightsWithThePmfTheyReport) {
  std::vector<Light> lights = mixed_lights();
  lights.push_back(DirectionalLight{normalize(Vec3(-0.5f, -0.2f, 0.4f)), RGB(0.3f), 0.999f, 10.0f});  // a second sun
  for (LightSamplerKind kind : {LightSamplerKind::kTree, LightSamplerKind::kTreeFixedShare}) {
    const LightSampler tree(kind, lights);
    for (const PointQuery& q : point_queries())
      check_sampling(
          lights.size(), [&](float u) { return tree.sample(q.p, q.n, u); },
          [&](int l) { return tree.pmf(q.p, q.n, l); }, light_sampler_name(kind));
  }
}

TEST(LightTree, SegmentsChooseLightsWithThePmfTheyReport) {
  std::vector<Light> lights = mixed_lights();
  lights.push_back(DirectionalLight{normalize(Vec3(-0.5f, -0.2f, 0.4f)), RGB(0.3f), 0.999f, 10.0f});
  for (LightSamplerKind kind : {LightSamplerKind::kTree, LightSamplerKind::kTreeFixedShare}) {
    const LightSampler tree(kind, lights);
    for (const Ray& s : segment_queries())
      check_sampling(
          lights.size(), [&](float u) { return tree.sample_segment(s, u); },
          [&](int l) { return tree.pmf_segment(s, l); }, light_sampler_name(kind));
  }
}

// Adaptive splitting: over many u, each light is among the choices as often as choice_pmf says
// (a Bernoulli count: within 5 standard errors), every choice reports that pmf exactly, no light
// is chosen twice, and near the lights (receivers inside the tree's nodes) it does split.
template <class Choose, class Pmf>
void check_split(size_t light_count, const Choose& choose, const Pmf& pmf, const char* what, int* most) {
  constexpr int kDraws = 20000;
  std::vector<double> included(light_count, 0.0);
  Pcg32 rng(3, 9);
  int mismatches = 0;
  for (int s = 0; s < kDraws; ++s) {
    const LightChoices cs = choose(rng.next_float());
    *most = std::max(*most, cs.count);
    std::vector<bool> seen(light_count, false);
    for (const LightChoice& c : cs) {
      ASSERT_FALSE(seen[size_t(c.light)]) << what;
      seen[size_t(c.light)] = true;
      included[size_t(c.light)] += 1.0 / kDraws;
      if (c.pmf != pmf(c.light)) ++mismatches;
    }
  }
  EXPECT_EQ(mismatches, 0) << what;
  for (size_t i = 0; i < light_count; ++i) {
    const double p = pmf(int(i));
    EXPECT_LE(p, 1.0 + 1e-6) << what;
    EXPECT_NEAR(included[i], p, 5.0 * std::sqrt(p * (1.0 - std::min(p, 1.0)) / kDraws) + 1e-6)
        << what << " light " << i;
  }
}

TEST(LightTree, SplitChoicesFollowTheirPmfs) {
  const std::vector<Light> lights = mixed_lights();
  const LightSampler tree(LightSamplerKind::kTree, lights);
  int most = 0;
  for (const PointQuery& q : point_queries())
    check_split(
        lights.size(), [&](float u) { return tree.choose(q.p, q.n, u); },
        [&](int l) { return tree.choice_pmf(q.p, q.n, l); }, "point", &most);
  for (const Ray& s : segment_queries())
    check_split(
        lights.size(), [&](float u) { return tree.choose_segment(s, u); },
        [&](int l) { return tree.choice_pmf_segment(s, l); }, "segment", &most);
  EXPECT_GT(most, 1);  // the receivers sit among the lights: some nodes split
  EXPECT_LE(most, 1 << LightTree::kSplitDepth);
}

// 64 lamps spread over 100 m and a receiver half a metre from one: the tree must find it (with
// splitting it is among the choices with probability 0.5 or more; uniform choice gives 1/64).
TEST(LightTree, ANearLampIsFoundAmongMany) {
  std::vector<Light> lights;
  Pcg32 rng(5, 1);
  for (int i = 0; i < 64; ++i) lights.push_back(PointLight{random_point(rng, 50), RGB(1.0f + rng.next_float())});
  const Vec3 lamp = std::get<PointLight>(lights[17]).position;
  const LightSampler tree(LightSamplerKind::kTree, lights);
  const Vec3 p = lamp + Vec3(0.5f, 0, 0);
  const float split = tree.choice_pmf(p, Vec3(0.0f), 17), single = tree.pmf(p, Vec3(0.0f), 17);
  EXPECT_GE(split, 0.5f);
  EXPECT_GE(single, 10.0f / 64.0f);  // one choice (no splitting): still 10x uniform's
  EXPECT_GT(split, single);          // the split finds it more often (0.28 for one choice)
}

// A faint sky over a large scene (a 1 km ground plane) beside a lamp a metre away: the sky's
// power grows as the scene's radius squared, so a share by power gave it 90 % of the samples;
// weighed at the receiver the lamp gets at least 90 % (its irradiance is ~25x the sky's).
TEST(LightSampler, ALargeScenesSkyDoesNotStarveANearLamp) {
  std::vector<Light> lights{PointLight{{0, 1, 0}, RGB(8.0f)}, EnvironmentLight{RGB(0.1f), 1000.0f}};
  const LightSampler tree(LightSamplerKind::kTree, lights), fixed(LightSamplerKind::kTreeFixedShare, lights);
  const Vec3 p(0, 0, 0), n(0, 1, 0);
  EXPECT_GE(tree.pmf(p, n, 0), 0.9f);
  EXPECT_LE(fixed.pmf(p, n, 0), 0.1f + 1e-6f);  // the former rule, for the record
  EXPECT_NEAR(tree.pmf(p, n, 0) + tree.pmf(p, n, 1), 1.0f, 1e-6f);
  // Far from the lamp the sky takes over again.
  EXPECT_GE(tree.pmf({300, 0, 0}, n, 1), 0.9f);
  // In a medium, along a segment passing the lamp, the lamp still leads.
  const Ray past{{-2, 1.2f, 0}, {1, 0, 0}, 0.0f, 4.0f};
  EXPECT_GE(tree.pmf_segment(past, 0), 0.5f);
}

TEST(LightTree, UniformAndPowerFollowTheirPmfs) {
  const std::vector<Light> lights = mixed_lights();
  const LightSampler uniform(LightSamplerKind::kUniform, lights), power(LightSamplerKind::kPower, lights);
  check_sampling(
      lights.size(), [&](float u) { return uniform.sample({}, {}, u); }, [&](int l) { return uniform.pmf({}, {}, l); },
      "uniform");
  check_sampling(
      lights.size(), [&](float u) { return power.sample({}, {}, u); }, [&](int l) { return power.pmf({}, {}, l); },
      "power");
  EXPECT_FLOAT_EQ(uniform.pmf({}, {}, 3), 1.0f / float(lights.size()));
}

// Without a normal, every finite light but the zero-power one and the spots and one-sided
// emitters facing away keeps a path of non-zero importance; where nothing is cut off the
// pmfs sum to one.
TEST(LightTree, PmfsSumToOneWhereNoNodeIsCutOff) {
  std::vector<Light> lights;
  Pcg32 rng(3, 9);
  for (int i = 0; i < 300; ++i) lights.push_back(PointLight{random_point(rng, 20), RGB(rng.next_float() + 0.1f)});
  for (int i = 0; i < 40; ++i) lights.push_back(SphereLight{random_point(rng, 20), 0.3f, RGB(1)});
  lights.push_back(EnvironmentLight{RGB(0.01f), 30.0f});
  const LightSampler tree(LightSamplerKind::kTree, lights);
  for (const PointQuery& q : point_queries()) {
    double sum = 0.0;
    for (size_t i = 0; i < lights.size(); ++i) sum += tree.pmf(q.p, {}, int(i));
    EXPECT_NEAR(sum, 1.0, 1e-5);
  }
  for (const Ray& s : segment_queries()) {
    double sum = 0.0;
    for (size_t i = 0; i < lights.size(); ++i) sum += tree.pmf_segment(s, int(i));
    EXPECT_NEAR(sum, 1.0, 1e-5);
  }
}

// Whether some point of the light sends light to p (arriving on the side n faces, if n != 0).
bool can_light(const Light& light, Vec3 p, Vec3 n, Pcg32& rng) {
  for (int k = 0; k < 256; ++k) {
    const auto ls = sample_light(light, p, {rng.next_float(), rng.next_float()});
    if (ls && !ls->radiance.is_black() && ls->pdf > 0.0f && (length_squared(n) == 0.0f || dot(n, ls->wi) > 0.0f))
      return true;
  }
  return false;
}

TEST(LightTree, EveryLightThatCanContributeHasPositivePmf) {
  const std::vector<Light> lights = mixed_lights();
  const LightSampler tree(LightSamplerKind::kTree, lights);
  Pcg32 rng(5, 1);
  int checked = 0;
  for (int q = 0; q < 40; ++q) {
    const Vec3 p = random_point(rng, 7);
    const Vec3 n = q % 4 == 0 ? Vec3() : random_unit(rng);
    for (size_t i = 0; i < lights.size(); ++i) {
      if (!can_light(lights[i], p, n, rng)) continue;
      ++checked;
      EXPECT_GT(tree.pmf(p, n, int(i)), 0.0f) << "light " << i << " at query " << q;
    }
    const Ray segment{p, random_unit(rng), 0.0f, 2.0f + 10.0f * rng.next_float()};
    for (size_t i = 0; i < lights.size(); ++i) {
      bool lit = false;
      for (int k = 0; k < 32 && !lit; ++k)
        lit = can_light(lights[i], segment.at(segment.tmin + (k + 0.5f) / 32 * (segment.tmax - segment.tmin)), {},
                        rng);
      if (!lit) continue;
      ++checked;
      EXPECT_GT(tree.pmf_segment(segment, int(i)), 0.0f) << "light " << i << " on segment " << q;
    }
  }
  EXPECT_GT(checked, 1000);  // the check above actually ran
}

// A single omnidirectional point: the segment importance is power x the integral of 1/d^2.
TEST(LightTree, SegmentImportanceOfAPointIsTheInverseSquareIntegral) {
  const LightTree::Node node = LightTree::make_node(*light_bounds(PointLight{{1, 2, 0}, RGB(1.0f)}));
  const Ray s{{-3, 0, 0}, {1, 0, 0}, 0.5f, 7.0f};
  double integral = 0.0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const float t = s.tmin + (i + 0.5f) * (s.tmax - s.tmin) / n;
    integral += 1.0 / double(length_squared(s.at(t) - Vec3(1, 2, 0)));
  }
  integral *= (s.tmax - s.tmin) / n;
  EXPECT_NEAR(LightTree::importance(node, s), node.phi * integral, 1e-4 * node.phi * integral);
  // At a point, power / d^2.
  EXPECT_NEAR(LightTree::importance(node, Vec3(1, 2, 3), Vec3()), node.phi / 9.0f, 1e-5f * node.phi);
}

// A spot's cone: zero outside it (beyond the bounding cone), positive inside.
TEST(LightTree, SpotConeBoundsTheImportance) {
  SpotLight spot{{0, 0, 0}, {0, -1, 0}};
  spot.cos_outer = std::cos(radians(30));
  spot.cos_inner = std::cos(radians(20));
  spot.intensity = RGB(1);
  const LightTree::Node node = LightTree::make_node(*light_bounds(spot));
  EXPECT_GT(LightTree::importance(node, Vec3(0.5f, -2, 0), Vec3()), 0.0f);
  EXPECT_EQ(LightTree::importance(node, Vec3(2, -2, 0), Vec3()), 0.0f);
  EXPECT_EQ(LightTree::importance(node, Vec3(0, 2, 0), Vec3()), 0.0f);
  // A segment that crosses the beam below the light is lit; one above it is not.
  EXPECT_GT(LightTree::importance(node, Ray{{-5, -3, 0}, {1, 0, 0}, 0.0f, 10.0f}), 0.0f);
  EXPECT_EQ(LightTree::importance(node, Ray{{-5, 1, 0}, {1, 0, 0}, 0.0f, 10.0f}), 0.0f);
  // A receiver facing away from the light gets nothing.
  EXPECT_EQ(LightTree::importance(node, Vec3(0, -2, 0), Vec3(0, -1, 0)), 0.0f);
}

TEST(LightSampler, NamesRoundTrip) {
  for (const auto& [k, name] : kLightSamplerNames) EXPECT_EQ(light_sampler_from_name(light_sampler_name(k)), k);
  EXPECT_FALSE(light_sampler_from_name("bvh"));
}

TEST(LightSampler, NoLightsChoosesNothing) {
  const std::vector<Light> none;
  for (const auto& [k, name] : kLightSamplerNames) {
    const LightSampler s(k, none);
    EXPECT_LT(s.sample({}, {}, 0.5f).light, 0);
    EXPECT_LT(s.sample_segment(Ray{{}, {1, 0, 0}, 0, 1}, 0.5f).light, 0);
  }
}

}  // namespace
}  // namespace caligo
