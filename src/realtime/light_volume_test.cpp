#include "realtime/light_volume.h"

#include <gtest/gtest.h>

#include <functional>

#include "core/rng.h"
#include "core/testing/random_rays.h"

namespace caligo {
namespace {

using testing::expect_matches_brute_force;
using testing::random_direction;
using testing::random_in_cube;

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
    const ShadedLight shaded = *shaded_light(light);
    const PixelRect rect = light_screen_bounds(shaded, view);
    culled += (rect.x1 - rect.x0) * (rect.y1 - rect.y0) < 48 * 32;
    for (int y = 0; y < 32; ++y) {
      for (int x = 0; x < 48; ++x) {
        const Ray r = view.ray({x + 0.5f, y + 0.5f});
        if (!light_volume_interval(shaded, r.origin, r.direction, 0.0f, 1e4f)) continue;
        EXPECT_TRUE(x >= rect.x0 && x < rect.x1 && y >= rect.y0 && y < rect.y1)
            << "trial " << trial << " pixel " << x << "," << y;
      }
    }
  }
  EXPECT_GT(culled, 20);
}

}  // namespace
}  // namespace caligo
