// light_reach: the intervals where a light can send light, against point membership tested
// densely along random rays.
#include <gtest/gtest.h>

#include <cmath>

#include "core/rng.h"
#include "lights/light_reach.h"

namespace caligo {
namespace {

Vec3 random_dir(Pcg32& rng) {
  for (;;) {
    const Vec3 v{rng.next_float() * 2 - 1, rng.next_float() * 2 - 1, rng.next_float() * 2 - 1};
    const float l2 = length_squared(v);
    if (l2 > 1e-3f && l2 <= 1.0f) return v / std::sqrt(l2);
  }
}

// Every point of [tmin, tmax] (1000 samples) is inside the interval exactly when `inside`
// says so, up to one sample spacing at the ends.
template <typename Inside>
void expect_matches(std::optional<RayRange> got, Vec3 o, Vec3 d, float tmin, float tmax, Inside inside) {
  const int n = 1000;
  const float step = (tmax - tmin) / n;
  for (int i = 0; i <= n; ++i) {
    const float t = tmin + step * i;
    const bool in = inside(o + d * t);
    const bool in_interval = got && t >= got->t0 && t <= got->t1;
    if (in == in_interval) continue;
    // Allow disagreement within one step of an end.
    ASSERT_TRUE(got.has_value()) << "t " << t;
    EXPECT_LT(std::min(std::abs(t - got->t0), std::abs(t - got->t1)), 1.01f * step) << "t " << t;
  }
}

TEST(LightReach, SpotConeAndRange) {
  Pcg32 rng(1, 1);
  for (int i = 0; i < 300; ++i) {
    SpotLight s;
    s.position = {rng.next_float() * 2 - 1, 2, rng.next_float() * 2 - 1};
    s.direction = random_dir(rng);
    s.cos_outer = std::cos(0.05f + 1.4f * rng.next_float());
    s.cos_inner = std::min(1.0f, s.cos_outer + 0.01f);
    s.range = i % 2 ? kInfinity : 1.0f + 4.0f * rng.next_float();
    const Vec3 o{rng.next_float() * 8 - 4, rng.next_float() * 8 - 4, rng.next_float() * 8 - 4};
    // Aim near the apex half of the time, so the ray crosses the cone.
    const Vec3 d = i % 2 ? normalize(s.position + s.direction * 2.0f + random_dir(rng) * 0.5f - o) : random_dir(rng);
    const float tmin = rng.next_float(), tmax = tmin + 12.0f;
    expect_matches(light_reach(s, o, d, tmin, tmax), o, d, tmin, tmax, [&](Vec3 p) {
      const Vec3 v = p - s.position;
      return dot(v, s.direction) >= s.cos_outer * length(v) && length(v) <= s.range;
    });
  }
}

TEST(LightReach, OneSidedAreaLightsReachTheirFrontHalfSpace) {
  Pcg32 rng(2, 2);
  for (int i = 0; i < 200; ++i) {
    const QuadLight q{{0, 1, 0}, random_dir(rng), random_dir(rng), RGB(1.0f), false};
    const TriangleLight t{{0, 1, 0}, random_dir(rng), random_dir(rng), RGB(1.0f), false};
    const Vec3 o{rng.next_float() * 4 - 2, rng.next_float() * 4 - 2, rng.next_float() * 4 - 2};
    const Vec3 d = random_dir(rng);
    const Vec3 nq = cross(q.edge1, q.edge2), nt = cross(t.p1 - t.p0, t.p2 - t.p0);
    expect_matches(light_reach(q, o, d, 0, 8), o, d, 0, 8, [&](Vec3 p) { return dot(p - q.corner, nq) > 0; });
    expect_matches(light_reach(t, o, d, 0, 8), o, d, 0, 8, [&](Vec3 p) { return dot(p - t.p0, nt) > 0; });
    QuadLight two = q;
    two.two_sided = true;
    const auto all = light_reach(two, o, d, 0, 8);
    ASSERT_TRUE(all.has_value());
    EXPECT_EQ(all->t0, 0.0f);
    EXPECT_EQ(all->t1, 8.0f);
  }
}

TEST(LightReach, PointRangeSphereAndUnboundedLights) {
  const PointLight bounded{{0, 0, 0}, RGB(1.0f), 2.0f, {}};
  const auto r = light_reach(bounded, {-5, 1, 0}, {1, 0, 0}, 0, 10);
  ASSERT_TRUE(r.has_value());
  EXPECT_NEAR(r->t0, 5 - std::sqrt(3.0f), 1e-5f);
  EXPECT_NEAR(r->t1, 5 + std::sqrt(3.0f), 1e-5f);
  EXPECT_FALSE(light_reach(bounded, {-5, 3, 0}, {1, 0, 0}, 0, 10).has_value());
  const auto whole = light_reach(SphereLight{{0, 0, 0}, 1.0f, RGB(1.0f), false}, {-5, 3, 0}, {1, 0, 0}, 1, 10);
  ASSERT_TRUE(whole.has_value());
  EXPECT_EQ(whole->t0, 1.0f);
  EXPECT_EQ(whole->t1, 10.0f);
}

}  // namespace
}  // namespace caligo
