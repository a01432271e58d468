// The shape of delta-light emission (light_profile.h): range window, cone, gobo projection,
// IES factor, the box light, and agreement of sample_light with delta_arrival.
#include "lights/light_profile.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "core/math.h"
#include "core/rng.h"
#include "lights/gobo.h"
#include "lights/ies.h"
#include "lights/light_sample.h"

namespace caligo {
namespace {

// 2x2 image, row 0 at the top: red green / blue white.
std::shared_ptr<const GoboImage> quadrant_image() {
  return std::make_shared<const GoboImage>(
      2, 2, std::vector<RGB>{RGB(1, 0, 0), RGB(0, 1, 0), RGB(0, 0, 1), RGB(1, 1, 1)});
}

void expect_rgb_near(RGB a, RGB b, float tol) {
  EXPECT_NEAR(a.r, b.r, tol);
  EXPECT_NEAR(a.g, b.g, tol);
  EXPECT_NEAR(a.b, b.b, tol);
}

TEST(RangeWindow, MatchesTheFormulaAndEndsAtTheRange) {
  EXPECT_FLOAT_EQ(range_window(0.0f, 4.0f), 1.0f);
  EXPECT_FLOAT_EQ(range_window(2.0f, 4.0f), sqr(1.0f - 1.0f / 16.0f));
  EXPECT_FLOAT_EQ(range_window(4.0f, 4.0f), 0.0f);
  EXPECT_FLOAT_EQ(range_window(5.0f, 4.0f), 0.0f);
  EXPECT_FLOAT_EQ(range_window(1e6f, kInfinity), 1.0f);
  // Monotonic decreasing inside the range.
  float previous = 1.0f;
  for (float d = 0.1f; d < 4.0f; d += 0.1f) {
    EXPECT_LE(range_window(d, 4.0f), previous);
    previous = range_window(d, 4.0f);
  }
}

TEST(RangeWindow, PointLightIsInverseSquareTimesWindow) {
  PointLight light{{0, 0, 0}, RGB(8.0f), 4.0f};
  const auto a = delta_arrival(light, {0, 2, 0});
  ASSERT_TRUE(a);
  EXPECT_FLOAT_EQ(a->radiance.r, 8.0f / 4.0f * sqr(1.0f - 1.0f / 16.0f));
  EXPECT_FALSE(delta_arrival(light, {0, 4.5f, 0}));
}

TEST(GoboImage, BilinearAtCentresMidpointsAndWrapping) {
  const auto image = quadrant_image();
  // Pixel centres: u = 0.25/0.75, v = 0.75 (top row) / 0.25 (bottom row).
  expect_rgb_near(image->lookup({0.25f, 0.75f}), RGB(1, 0, 0), 1e-6f);
  expect_rgb_near(image->lookup({0.75f, 0.75f}), RGB(0, 1, 0), 1e-6f);
  expect_rgb_near(image->lookup({0.25f, 0.25f}), RGB(0, 0, 1), 1e-6f);
  expect_rgb_near(image->lookup({0.5f, 0.75f}), RGB(0.5f, 0.5f, 0), 1e-6f);
  // u = 0 lies between the last column and the first (wrap).
  expect_rgb_near(image->lookup({0.0f, 0.75f}), RGB(0.5f, 0.5f, 0), 1e-6f);
  expect_rgb_near(image->lookup({1.3f, -2.6f}), image->lookup({0.3f, 0.4f}), 1e-5f);
  expect_rgb_near(image->mean(), RGB(0.5f, 0.5f, 0.5f), 1e-6f);
  EXPECT_THROW(GoboImage(2, 2, std::vector<RGB>(3)), std::invalid_argument);
}

TEST(GoboFilter, RotationAboutTheCentreThenOffset) {
  Gobo gobo{quadrant_image()};
  expect_rgb_near(gobo_filter(Gobo{}, {0.3f, 0.3f}), RGB(1.0f), 0.0f);  // no image: white
  expect_rgb_near(gobo_filter(gobo, {0.75f, 0.75f}), RGB(0, 1, 0), 1e-6f);
  // +90 degrees takes the top-right quadrant's centre (0.25, 0.25 from the centre) to (-0.25, 0.25):
  // the top-left texel, red.
  gobo.rotation = radians(90.0f);
  expect_rgb_near(gobo_filter(gobo, {0.75f, 0.75f}), RGB(1, 0, 0), 1e-5f);
  // Then shifting by half the texture moves to the top-right texel.
  gobo.offset = {0.5f, 0.0f};
  expect_rgb_near(gobo_filter(gobo, {0.75f, 0.75f}), RGB(0, 1, 0), 1e-5f);
}

SpotLight spot_down() {
  SpotLight spot{{0, 5, 0}, {0, -1, 0}, std::cos(radians(20.0f)), std::cos(radians(30.0f)), RGB(10.0f)};
  spot.up = {0, 0, -1};  // right = cross(direction, up) = +x
  return spot;
}

TEST(SpotGoboUv, CentreAndOuterConeEdges) {
  const SpotLight spot = spot_down();
  const Vec2 centre = spot_gobo_uv(spot, spot.direction);
  EXPECT_NEAR(centre.x, 0.5f, 1e-6f);
  EXPECT_NEAR(centre.y, 0.5f, 1e-6f);
  const float a = radians(30.0f);
  const Vec2 right = spot_gobo_uv(spot, {std::sin(a), -std::cos(a), 0});
  EXPECT_NEAR(right.x, 1.0f, 1e-5f);
  EXPECT_NEAR(right.y, 0.5f, 1e-5f);
  const Vec2 left = spot_gobo_uv(spot, {-std::sin(a), -std::cos(a), 0});
  EXPECT_NEAR(left.x, 0.0f, 1e-5f);
  const Vec2 up = spot_gobo_uv(spot, {0, -std::cos(a), -std::sin(a)});
  EXPECT_NEAR(up.x, 0.5f, 1e-5f);
  EXPECT_NEAR(up.y, 1.0f, 1e-5f);
  // Half-way in tangent lands half-way to the edge.
  const Vec3 w = normalize(Vec3(0.5f * std::tan(a), -1.0f, 0));
  EXPECT_NEAR(spot_gobo_uv(spot, w).x, 0.75f, 1e-5f);
}

TEST(SpotLight, GoboFiltersTheArrivingLight) {
  SpotLight spot = spot_down();
  spot.cos_inner = std::cos(radians(29.0f));
  spot.gobo.image = quadrant_image();
  // A receiver below, towards +x and -z (gobo up): the top-right texel, green.
  const float t = std::tan(radians(12.0f));
  const Vec3 receiver{5.0f * t, 0.0f, -5.0f * t};
  const auto a = delta_arrival(spot, receiver);
  ASSERT_TRUE(a);
  const float d2 = length_squared(spot.position - receiver);
  const RGB expected = spot.intensity * spot.gobo.image->lookup(spot_gobo_uv(spot, -a->wi)) / d2;
  expect_rgb_near(a->radiance, expected, 1e-6f);
  EXPECT_GT(a->radiance.g, 0.5f * 10.0f / d2);
  EXPECT_LT(a->radiance.r, a->radiance.g);
}

TEST(SpotLight, SampleLightEqualsDeltaArrival) {
  SpotLight spot = spot_down();
  spot.gobo.image = quadrant_image();
  spot.gobo.rotation = 0.3f;
  spot.range = 9.0f;
  Pcg32 rng(3, 5);
  int lit = 0;
  for (int i = 0; i < 500; ++i) {
    const Vec3 p{8 * rng.next_float() - 4, 5 * rng.next_float() - 3, 8 * rng.next_float() - 4};
    const auto a = delta_arrival(spot, p);
    const auto s = sample_light(spot, p, {rng.next_float(), rng.next_float()});
    ASSERT_EQ(a.has_value(), s.has_value());
    if (!a) continue;
    ++lit;
    EXPECT_EQ(s->radiance, a->radiance);
    EXPECT_EQ(s->wi, a->wi);
    EXPECT_EQ(s->distance, a->distance);
    EXPECT_TRUE(s->delta);
    EXPECT_EQ(s->pdf, 1.0f);
  }
  EXPECT_GT(lit, 20);
}

BoxLight box_light() {
  // Face centred at (0, 10, 0), 4 m wide (x) and 2 m high (z), shining down 8 m.
  return BoxLight{{0, 10, 0}, {0, -1, 0}, {0, 0, -1}, 2.0f, 1.0f, 8.0f, RGB(3, 2, 1)};
}

TEST(BoxLight, InsideGetsTheIrradianceFromTheFace) {
  const BoxLight box = box_light();
  const auto a = delta_arrival(box, {1.5f, 4.0f, 0.5f});
  ASSERT_TRUE(a);
  EXPECT_EQ(a->radiance, RGB(3, 2, 1));
  EXPECT_EQ(a->wi, Vec3(0, 1, 0));
  EXPECT_FLOAT_EQ(a->distance, 6.0f);
  // The shadow ray's end lies on the emitting face.
  const Vec3 end = Vec3(1.5f, 4.0f, 0.5f) + a->wi * a->distance;
  EXPECT_FLOAT_EQ(end.y, 10.0f);
}

TEST(BoxLight, OutsideTheBoxGetsNothing) {
  const BoxLight box = box_light();
  EXPECT_FALSE(delta_arrival(box, {2.5f, 4.0f, 0.0f}));   // beyond the width
  EXPECT_FALSE(delta_arrival(box, {0.0f, 4.0f, 1.2f}));   // beyond the height
  EXPECT_FALSE(delta_arrival(box, {0.0f, 11.0f, 0.0f}));  // behind the face
  EXPECT_FALSE(delta_arrival(box, {0.0f, 1.5f, 0.0f}));   // past the range
  EXPECT_TRUE(delta_arrival(box, {0.0f, 2.5f, 0.0f}));
}

TEST(BoxLight, GoboMapsTheFaceToTheUnitSquare) {
  BoxLight box = box_light();
  box.gobo.image = quadrant_image();
  // right = cross(direction, up) = cross(-y, -z) = +x; up = -z. The texel centre (0.75, 0.75)
  // (top right, green) sits at x = +1, z = -0.5.
  const auto a = delta_arrival(box, {1.0f, 5.0f, -0.5f});
  ASSERT_TRUE(a);
  expect_rgb_near(a->radiance, RGB(0, 2, 0), 1e-5f);
  const auto s = sample_light(box, {1.0f, 5.0f, -0.5f}, {});
  ASSERT_TRUE(s);
  EXPECT_EQ(s->radiance, a->radiance);
  EXPECT_FLOAT_EQ(s->distance, 5.0f);
}

TEST(BoxLight, PowerIsIrradianceTimesFaceArea) { EXPECT_NEAR(power(box_light()), 2.0f * 4.0f * 2.0f, 1e-5f); }

TEST(IesFactor, ProfileAlongItsAxis) {
  const auto profile = std::make_shared<const IesProfile>(
      IesProfile::parse("TILT=NONE\n1 1000 1 3 1 1 2 0 0 0\n1 1 100\n0 90 180\n0\n100 50 0\n", "t.ies"));
  const IesAttachment ies{profile, {0, 0, 1}};
  EXPECT_FLOAT_EQ(ies_factor(ies, {0, 0, 1}), 1.0f);
  EXPECT_NEAR(ies_factor(ies, {1, 0, 0}), 0.5f, 1e-5f);
  EXPECT_NEAR(ies_factor(ies, {0, 0, -1}), 0.0f, 1e-5f);
  EXPECT_FLOAT_EQ(ies_factor(IesAttachment{}, {1, 0, 0}), 1.0f);
  PointLight light{{0, 0, 0}, RGB(4.0f), kInfinity, ies};
  const auto side = delta_arrival(light, {2, 0, 0});
  ASSERT_TRUE(side);
  EXPECT_NEAR(side->radiance.r, 4.0f * 0.5f / 4.0f, 1e-5f);
  EXPECT_NEAR(power(light), 4.0f * kPi * 4.0f * profile->mean(), 1e-3f);
}

}  // namespace
}  // namespace caligo
