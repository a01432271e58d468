#include "realtime/light_volume.h"

#include <gtest/gtest.h>

#include <functional>

#include "core/rng.h"
#include "realtime/test_random.h"

namespace caligo {
namespace {

using testing::random_direction;
using testing::random_in_cube;

// Brute force: the first and last of kSteps dense samples along [tmin, tmax] where `inside`
// holds. The analytic interval must contain every inside sample and start/end within one
// sample spacing of the first/last one (the sets are convex, so there are no gaps).
void expect_matches_brute_force(const std::function<bool(Vec3)>& inside, Vec3 o, Vec3 d, float tmin,
                                float tmax, std::optional<TInterval> got, int ray) {
  constexpr int kSteps = 20000;
  const float dt = (tmax - tmin) / kSteps;
  float first = kInfinity, last = -kInfinity;
  for (int i = 0; i <= kSteps; ++i) {
    const float t = tmin + dt * float(i);
    if (inside(o + d * t)) {
      first = std::min(first, t);
      last = std::max(last, t);
    }
  }
  if (first == kInfinity) {
    // Nothing sampled inside: the interval may only be a sliver thinner than the spacing.
    if (got) {
      EXPECT_LT(got->t1 - got->t0, 2.0f * dt) << "ray " << ray;
    }
    return;
  }
  ASSERT_TRUE(got.has_value()) << "ray " << ray << " brute force [" << first << ", " << last << "]";
  const float tol = dt * 1.01f + 1e-4f;
  EXPECT_LE(got->t0, first + 1e-4f) << "ray " << ray;
  EXPECT_GE(got->t1, last - 1e-4f) << "ray " << ray;
  EXPECT_GT(got->t0, first - tol) << "ray " << ray;
  EXPECT_LT(got->t1, last + tol) << "ray " << ray;
}

TEST(LightVolume, SphereIntervalMatchesBruteForce) {
  Pcg32 rng(7, 1);
  int hits = 0;
  for (int ray = 0; ray < 300; ++ray) {
    const Vec3 c = random_in_cube(rng, 2.0f), o = random_in_cube(rng, 6.0f);
    const float r = 0.5f + 3.0f * rng.next_float();
    // Half the rays aim near the sphere (hits, grazing misses), half go anywhere.
    const Vec3 d = ray % 2 ? normalize(c + random_in_cube(rng, r * 1.2f) - o) : random_direction(rng);
    const float tmin = rng.next_float() * 2.0f, tmax = tmin + 15.0f * rng.next_float();
    const auto got = ray_sphere_interval(o, d, c, r, tmin, tmax);
    hits += got.has_value();
    expect_matches_brute_force([&](Vec3 p) { return length_squared(p - c) <= r * r; }, o, d, tmin, tmax, got,
                               ray);
  }
  EXPECT_GT(hits, 60);  // the random rays exercise both outcomes
  EXPECT_LT(hits, 290);
}

TEST(LightVolume, ConeIntervalMatchesBruteForce) {
  Pcg32 rng(11, 2);
  int hits = 0;
  for (int ray = 0; ray < 400; ++ray) {
    const Vec3 apex = random_in_cube(rng, 1.0f), axis = random_direction(rng);
    const float cos_half = std::cos(radians(5.0f + 80.0f * rng.next_float()));
    // Half the rays start near the apex: both nappes, the apex itself and grazing rays.
    const Vec3 o = ray % 2 ? apex + random_in_cube(rng, 0.5f) : random_in_cube(rng, 6.0f);
    const Vec3 d = random_direction(rng);
    const float tmin = 0.0f, tmax = 12.0f;
    const auto got = ray_cone_interval(o, d, apex, axis, cos_half, tmin, tmax);
    hits += got.has_value();
    expect_matches_brute_force(
        [&](Vec3 p) {
          const Vec3 v = p - apex;
          return dot(v, axis) >= cos_half * length(v);
        },
        o, d, tmin, tmax, got, ray);
  }
  EXPECT_GT(hits, 80);
  EXPECT_LT(hits, 390);
}

TEST(LightVolume, SpotIntervalIsConeAndRangeSphere) {
  Pcg32 rng(5, 3);
  for (int ray = 0; ray < 300; ++ray) {
    SpotLight spot;
    spot.position = random_in_cube(rng, 1.0f);
    spot.direction = random_direction(rng);
    spot.cos_outer = std::cos(radians(10.0f + 60.0f * rng.next_float()));
    spot.cos_inner = std::min(1.0f, spot.cos_outer + 0.05f);
    spot.range = 1.0f + 5.0f * rng.next_float();
    const Vec3 o = random_in_cube(rng, 5.0f), d = random_direction(rng);
    const auto got = light_volume_interval(spot, o, d, 0.0f, 12.0f);
    expect_matches_brute_force(
        [&](Vec3 p) {
          const Vec3 v = p - spot.position;
          return dot(v, spot.direction) >= spot.cos_outer * length(v) && length(v) <= spot.range;
        },
        o, d, 0.0f, 12.0f, got, ray);
  }
}

TEST(LightVolume, BoxLightIntervalMatchesBruteForce) {
  Pcg32 rng(3, 4);
  int hits = 0;
  for (int ray = 0; ray < 300; ++ray) {
    BoxLight box;
    box.position = random_in_cube(rng, 1.0f);
    box.direction = random_direction(rng);
    box.up = normalize(cross(box.direction, random_direction(rng)));
    box.half_width = 0.3f + 2.0f * rng.next_float();
    box.half_height = 0.3f + 2.0f * rng.next_float();
    box.range = 0.5f + 5.0f * rng.next_float();
    const Vec3 o = random_in_cube(rng, 5.0f);
    const Vec3 centre = box.position + box.direction * (0.5f * box.range);
    const Vec3 d = ray % 2 ? normalize(centre + random_in_cube(rng, 1.5f) - o) : random_direction(rng);
    const auto got = light_volume_interval(box, o, d, 0.0f, 12.0f);
    hits += got.has_value();
    const Vec3 right = cross(box.direction, box.up);
    expect_matches_brute_force(
        [&](Vec3 p) {
          const Vec3 l = p - box.position;
          const float z = dot(l, box.direction);
          return z >= 0.0f && z <= box.range && std::abs(dot(l, right)) <= box.half_width &&
                 std::abs(dot(l, box.up)) <= box.half_height;
        },
        o, d, 0.0f, 12.0f, got, ray);
  }
  EXPECT_GT(hits, 40);
}

TEST(LightVolume, PointWithoutRangeAndDirectionalCoverTheWholeRay) {
  PointLight point;
  const auto a = light_volume_interval(point, {}, {0, 0, 1}, 0.5f, 7.0f);
  ASSERT_TRUE(a);
  EXPECT_EQ(a->t0, 0.5f);
  EXPECT_EQ(a->t1, 7.0f);
  DirectionalLight sun{{0, -1, 0}, RGB(1.0f)};
  const auto b = light_volume_interval(sun, {}, {1, 0, 0}, 0.0f, 3.0f);
  ASSERT_TRUE(b);
  EXPECT_EQ(b->t1, 3.0f);
  EXPECT_FALSE(light_volume_interval(SphereLight{}, {}, {1, 0, 0}, 0.0f, 3.0f));
}

// Every pixel whose ray meets a light's volume lies inside light_screen_bounds (checked on
// every pixel of random views), and the bounds of small lights really are smaller than the image.
TEST(LightVolume, ScreenBoundsContainEveryPixelThatMeetsTheVolume) {
  Pcg32 rng(9, 9);
  int culled = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const View view = View::perspective_view(random_in_cube(rng, 3.0f), random_direction(rng), {0, 1, 0},
                                             radians(40.0f + 40.0f * rng.next_float()), {48, 32});
    Light light;
    const Vec3 pos = view.eye + view.forward * (3.0f + 8.0f * rng.next_float()) + random_in_cube(rng, 3.0f);
    if (trial % 3 == 0) {
      light = PointLight{pos, RGB(1.0f), 0.5f + 2.0f * rng.next_float(), {}};
    } else if (trial % 3 == 1) {
      SpotLight s;
      s.position = pos;
      s.direction = random_direction(rng);
      s.cos_outer = std::cos(radians(5.0f + 80.0f * rng.next_float()));
      s.range = 1.0f + 4.0f * rng.next_float();
      light = s;
    } else {
      BoxLight b;
      b.position = pos;
      b.direction = random_direction(rng);
      b.up = normalize(cross(b.direction, random_direction(rng)));
      b.half_width = 0.2f + rng.next_float();
      b.half_height = 0.2f + rng.next_float();
      b.range = 0.5f + 3.0f * rng.next_float();
      light = b;
    }
    const PixelRect rect = light_screen_bounds(light, view);
    culled += (rect.x1 - rect.x0) * (rect.y1 - rect.y0) < 48 * 32;
    for (int y = 0; y < 32; ++y) {
      for (int x = 0; x < 48; ++x) {
        const Ray r = view.ray({x + 0.5f, y + 0.5f});
        if (!light_volume_interval(light, r.origin, r.direction, 0.0f, 1e4f)) continue;
        EXPECT_TRUE(x >= rect.x0 && x < rect.x1 && y >= rect.y0 && y < rect.y1)
            << "trial " << trial << " pixel " << x << "," << y;
      }
    }
  }
  EXPECT_GT(culled, 20);
}

}  // namespace
}  // namespace caligo
