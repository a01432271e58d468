#include "realtime/light_volume_simd.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/rng.h"
#include "core/testing/random_rays.h"
#include "realtime/light_volume.h"

namespace caligo {
namespace {

using testing::random_direction;
using testing::random_in_cube;

struct Ray8 {
  Vec3 o[8], d[8];
  float tmax[8];
};

struct Counts {
  int lanes = 0, unsure = 0, hits = 0;
};

// Every lane the batch decides must agree with light_volume_interval (itself checked against
// brute force in light_volume_test.cpp): the same emptiness, and ends within 2e-4 of the
// ray's scale (its distance to the light plus its ends). A lane may only be empty on one
// side if the other side's interval is a sliver of that size.
void expect_matches_scalar(const ShadedLight& light, const Ray8& rays, Counts& counts) {
  using B = LightVolumeLanes::Batch;
  alignas(32) float v[7][8];
  for (int i = 0; i < 8; ++i) {
    v[0][i] = rays.o[i].x, v[1][i] = rays.o[i].y, v[2][i] = rays.o[i].z;
    v[3][i] = rays.d[i].x, v[4][i] = rays.d[i].y, v[5][i] = rays.d[i].z;
    v[6][i] = rays.tmax[i];
  }
  const LightVolumeLanes lanes(light);
  const auto got = lanes.intervals({B::load_aligned(v[0]), B::load_aligned(v[1]), B::load_aligned(v[2]),
                                    B::load_aligned(v[3]), B::load_aligned(v[4]), B::load_aligned(v[5]),
                                    B::load_aligned(v[6])});
  alignas(32) float t0[8], t1[8];
  got.t0.store_aligned(t0);
  got.t1.store_aligned(t1);
  alignas(32) float hit_lane[8], unsure_lane[8];
  xsimd::select(got.hit, B(1.0f), B(0.0f)).store_aligned(hit_lane);
  xsimd::select(got.unsure, B(1.0f), B(0.0f)).store_aligned(unsure_lane);
  for (int i = 0; i < 8; ++i) {
    ++counts.lanes;
    if (unsure_lane[i] != 0.0f) {
      ++counts.unsure;
      continue;
    }
    const auto want = light_volume_interval(light, rays.o[i], rays.d[i], 0.0f, rays.tmax[i]);
    // The lights sit within 5 m of the world origin.
    const float scale = 6.0f + length(rays.o[i]);
    auto tol_at = [&](float t) { return 2e-4f * (scale + std::abs(t)); };
    const bool has = hit_lane[i] != 0.0f;
    counts.hits += has;
    if (has && want) {
      EXPECT_NEAR(t0[i], want->t0, tol_at(want->t0)) << "lane " << i << " light " << light.index();
      EXPECT_NEAR(t1[i], want->t1, tol_at(want->t1)) << "lane " << i << " light " << light.index();
    } else if (has) {
      EXPECT_LT(t1[i] - t0[i], tol_at(t1[i])) << "lane " << i << " light " << light.index();
    } else if (want) {
      EXPECT_LT(want->t1 - want->t0, tol_at(want->t1)) << "lane " << i << " light " << light.index();
    }
  }
}

// Camera-like bundles (one origin, directions in a cone around a random view direction)
// and scattered rays (origins anywhere), near and far from the light.
Ray8 random_rays(Pcg32& rng, int round, Vec3 target) {
  Ray8 r;
  const Vec3 eye = random_in_cube(rng, round % 3 == 0 ? 20.0f : 6.0f);
  const Vec3 view = round % 2 ? normalize(target + random_in_cube(rng, 2.0f) - eye) : random_direction(rng);
  for (int i = 0; i < 8; ++i) {
    r.o[i] = round % 4 == 3 ? random_in_cube(rng, 6.0f) : eye;
    r.d[i] = normalize(view + random_in_cube(rng, 0.4f));
    r.tmax[i] = i == 7 ? 1e9f : 0.5f + 30.0f * rng.next_float();
  }
  return r;
}

TEST(LightVolumeSimd, SpotConesMatchScalar) {
  Pcg32 rng(21, 5);
  Counts counts;
  for (int round = 0; round < 3000; ++round) {
    SpotLight spot;
    spot.position = random_in_cube(rng, 3.0f);
    spot.direction = random_direction(rng);
    spot.cos_outer = std::cos(radians(3.0f + 100.0f * rng.next_float()));  // some beyond 90 degrees
    spot.cos_inner = std::min(1.0f, spot.cos_outer + 0.05f);
    spot.range = round % 5 == 0 ? kInfinity : 2.0f + 25.0f * rng.next_float();
    expect_matches_scalar(spot, random_rays(rng, round, spot.position + spot.direction * 3.0f), counts);
  }
  EXPECT_GT(counts.hits, counts.lanes / 10);  // both outcomes are exercised
  EXPECT_LT(counts.hits, counts.lanes * 9 / 10);
  EXPECT_LT(counts.unsure, counts.lanes / 50);  // and the float path decides nearly all lanes
}

// Rays that graze a cone: along one of its generators or tangent to it, a hair inside or
// outside the surface, far from the apex. Float alone gets these wrong; the lanes must come
// back unsure or right.
TEST(LightVolumeSimd, GrazingConeRaysAreUnsureOrRight) {
  Pcg32 rng(4, 9);
  Counts counts;
  for (int round = 0; round < 2000; ++round) {
    SpotLight spot;
    spot.position = random_in_cube(rng, 3.0f);
    spot.direction = random_direction(rng);
    const float half = radians(3.0f + 80.0f * rng.next_float());
    spot.cos_outer = std::cos(half);
    spot.range = kInfinity;
    const Frame f = Frame::from_z(spot.direction);
    Ray8 rays;
    for (int i = 0; i < 8; ++i) {
      const float phi = 2.0f * kPi * rng.next_float();
      const Vec3 radial = f.s * std::cos(phi) + f.t * std::sin(phi);
      const Vec3 generator = spot.direction * std::cos(half) + radial * std::sin(half);
      const Vec3 normal = radial * std::cos(half) - spot.direction * std::sin(half);  // outwards
      const Vec3 tangent = cross(spot.direction, radial);
      const float s = 1.0f + 20.0f * rng.next_float();
      const float off = (rng.next_float() - 0.5f) * (i % 2 ? 1e-3f : 1e-5f);
      const Vec3 touch = spot.position + generator * s + normal * off;
      const Vec3 d = i % 4 < 2 ? generator : tangent;
      rays.o[i] = touch - d * (5.0f * rng.next_float());
      rays.d[i] = d;
      rays.tmax[i] = 10.0f + 20.0f * rng.next_float();
    }
    expect_matches_scalar(spot, rays, counts);
  }
  EXPECT_GT(counts.unsure, 0);
}

TEST(LightVolumeSimd, PointBoxAndDirectionalMatchScalar) {
  Pcg32 rng(8, 6);
  Counts counts;
  for (int round = 0; round < 3000; ++round) {
    Light light;
    Vec3 target = random_in_cube(rng, 2.0f);
    switch (round % 4) {
      case 0:
        light = PointLight{target, RGB(1.0f), 0.5f + 10.0f * rng.next_float()};
        break;
      case 1: {
        BoxLight box;
        box.position = target;
        box.direction = random_direction(rng);
        box.up = normalize(cross(box.direction, random_direction(rng)));
        box.half_width = 0.3f + 2.0f * rng.next_float();
        box.half_height = 0.3f + 2.0f * rng.next_float();
        box.range = 0.5f + 10.0f * rng.next_float();
        target = box.position + box.direction * (0.5f * box.range);
        light = box;
        break;
      }
      case 2:
        light = PointLight{target, RGB(1.0f), kInfinity};
        break;
      default:
        light = DirectionalLight{random_direction(rng), RGB(1.0f)};
        break;
    }
    expect_matches_scalar(*shaded_light(light), random_rays(rng, round, target), counts);
  }
  EXPECT_GT(counts.hits, counts.lanes / 4);
  EXPECT_LT(counts.unsure, counts.lanes / 50);
}

// Rays along a box light's face (direction component exactly 0) take the scalar's
// inside-or-out rule.
TEST(LightVolumeSimd, AxisParallelRays) {
  BoxLight box;
  box.position = {0, 0, 0};
  box.direction = {0, 0, 1};
  box.up = {0, 1, 0};
  box.half_width = 1.0f;
  box.half_height = 1.0f;
  box.range = 4.0f;
  Ray8 rays;
  for (int i = 0; i < 8; ++i) {
    rays.o[i] = {-5.0f, float(i) * 0.5f - 1.75f, 2.0f};  // y from -1.75 to 1.75
    rays.d[i] = {1, 0, 0};
    rays.tmax[i] = 20.0f;
  }
  Counts counts;
  expect_matches_scalar(box, rays, counts);
  EXPECT_EQ(counts.hits, 4);  // |y| <= 1: the four middle rays
  EXPECT_EQ(counts.unsure, 0);
}

}  // namespace
}  // namespace caligo
