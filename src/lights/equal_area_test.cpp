// pbrt-v4's equal-area square: the mapping and its inverse, equal areas, and the resampling of
// a square image into Caligo's lat-long map through a rotation.
#include "lights/equal_area.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/math.h"
#include "lights/environment_map.h"

namespace caligo {
namespace {

TEST(EqualArea, TheMappingInvertsAndPutsThePolesWherePbrtDoes) {
  EXPECT_NEAR(equal_area_sphere_to_square({0, 0, 1}).x, 0.5f, 1e-6f);
  EXPECT_NEAR(equal_area_sphere_to_square({0, 0, 1}).y, 0.5f, 1e-6f);
  const Vec2 south = equal_area_sphere_to_square({0, 0, -1});
  EXPECT_TRUE((south.x == 0.0f || south.x == 1.0f) && (south.y == 0.0f || south.y == 1.0f));
  EXPECT_NEAR(equal_area_sphere_to_square({1, 0, 0}).x, 1.0f, 1e-6f);  // the equator is the diamond
  EXPECT_NEAR(equal_area_sphere_to_square({1, 0, 0}).y, 0.5f, 1e-6f);
  for (int i = 0; i < 2000; ++i) {
    const float z = 1.0f - 2.0f * (float(i) + 0.5f) / 2000.0f, phi = 2.39996f * float(i);
    const float s = std::sqrt(1.0f - z * z);
    const Vec3 d(s * std::cos(phi), s * std::sin(phi), z);
    const Vec2 p = equal_area_sphere_to_square(d);
    ASSERT_TRUE(p.x >= 0.0f && p.x <= 1.0f && p.y >= 0.0f && p.y <= 1.0f);
    const Vec3 back = equal_area_square_to_sphere(p);
    EXPECT_NEAR(length(back - d), 0.0f, 2e-4f) << i;
  }
}

// Equal areas: a regular grid over the square gives the moments of the uniform sphere
// (E[z] = 0, E[z^2] = 1/3, E[x y] = 0) to the grid's quadrature error.
TEST(EqualArea, EqualAreasOfTheSquareAreEqualSolidAngles) {
  const int n = 400;
  double z1 = 0, z2 = 0, xy = 0, upper = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Vec3 d = equal_area_square_to_sphere({(float(i) + 0.5f) / n, (float(j) + 0.5f) / n});
      z1 += d.z, z2 += double(d.z) * d.z, xy += double(d.x) * d.y, upper += d.z > 0 ? 1 : 0;
    }
  const double count = double(n) * n;
  EXPECT_NEAR(z1 / count, 0.0, 1e-4);
  EXPECT_NEAR(z2 / count, 1.0 / 3.0, 1e-4);
  EXPECT_NEAR(xy / count, 0.0, 1e-4);
  EXPECT_NEAR(upper / count, 0.5, 1e-2);  // the inner diamond is half the square
}

// f = 1 + z in light space, tabulated on a 64^2 square, turned so that light +z is world +y
// (pbrt's "Rotate -90 1 0 0"): the lat-long map reads 1 + w.y everywhere, to bilinear error.
TEST(EqualArea, ResamplingFollowsTheRotation) {
  const int n = 64;
  std::vector<RGB> square(size_t(n) * n);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const Vec3 d = equal_area_square_to_sphere({(x + 0.5f) / n, (y + 0.5f) / n});
      square[size_t(y) * n + size_t(x)] = RGB(1.0f + d.z, 1.0f + d.x, 1.0f);
    }
  const Transform to_world = Transform::rotate(radians(-90.0f), {1, 0, 0});
  const std::vector<RGB> latlong = equal_area_to_latlong(square, n, to_world);
  ASSERT_EQ(latlong.size(), size_t(2 * n) * n);
  double worst = 0;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < 2 * n; ++x) {
      const Vec3 w = latlong_to_direction({(x + 0.5f) / (2 * n), (y + 0.5f) / n});
      const Vec3 d = to_world.inverse_vector(w);
      const RGB v = latlong[size_t(y) * 2 * n + size_t(x)];
      worst = std::max({worst, double(std::abs(v.r - (1 + d.z))), double(std::abs(v.g - (1 + d.x)))});
      EXPECT_NEAR(v.r, 1.0f + w.y, 0.03f) << x << "," << y;  // light +z is world +y
    }
  EXPECT_LT(worst, 0.03);  // bilinear on a 64^2 square: about a texel of slope 1
}

}  // namespace
}  // namespace caligo
