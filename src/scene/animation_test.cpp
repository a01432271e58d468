// Keyframe interpolation and SceneDesc::at_time / duration.
#include "scene/animation.h"

#include <gtest/gtest.h>

#include <cmath>

#include "lights/light.h"

namespace caligo {
namespace {

void expect_vec_near(Vec3 a, Vec3 b, float tol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

const std::vector<float> kTimes{0.0f, 1.0f, 3.0f, 3.5f};
const std::vector<Vec3> kPoints{{0, 0, 0}, {1, 2, 0}, {4, 0, 1}, {4, 1, 1}};

TEST(InterpolateKeys, LinearIsPiecewiseLinearAndClamped) {
  expect_vec_near(interpolate_keys(kTimes, kPoints, Interpolation::linear, 0.5f), {0.5f, 1, 0}, 1e-6f);
  expect_vec_near(interpolate_keys(kTimes, kPoints, Interpolation::linear, 2.0f), {2.5f, 1, 0.5f}, 1e-6f);
  expect_vec_near(interpolate_keys(kTimes, kPoints, Interpolation::linear, -1.0f), kPoints.front(), 0.0f);
  expect_vec_near(interpolate_keys(kTimes, kPoints, Interpolation::linear, 9.0f), kPoints.back(), 0.0f);
  expect_vec_near(interpolate_keys({2.0f}, {{1, 2, 3}}, Interpolation::catmull_rom, 5.0f), {1, 2, 3}, 0.0f);
}

TEST(InterpolateKeys, CatmullRomPassesThroughEveryKey) {
  for (size_t i = 0; i < kTimes.size(); ++i)
    expect_vec_near(interpolate_keys(kTimes, kPoints, Interpolation::catmull_rom, kTimes[i]), kPoints[i],
                    1e-5f);
}

// Keys on a line at constant velocity (unevenly spaced in time) give exactly that motion.
TEST(InterpolateKeys, CatmullRomReproducesUniformMotion) {
  const Vec3 v{1.0f, -2.0f, 0.5f};
  std::vector<Vec3> p;
  for (float t : kTimes) p.push_back(v * t);
  for (float t = 0.0f; t <= 3.5f; t += 0.125f)
    expect_vec_near(interpolate_keys(kTimes, p, Interpolation::catmull_rom, t), v * t, 1e-5f);
}

// The velocity is continuous across a key (C1), unlike linear interpolation's.
TEST(InterpolateKeys, CatmullRomVelocityIsContinuousAtKeys) {
  const float h = 1e-3f;
  for (float key : {1.0f, 3.0f}) {
    const Vec3 before = (interpolate_keys(kTimes, kPoints, Interpolation::catmull_rom, key) -
                         interpolate_keys(kTimes, kPoints, Interpolation::catmull_rom, key - h)) /
                        h;
    const Vec3 after = (interpolate_keys(kTimes, kPoints, Interpolation::catmull_rom, key + h) -
                        interpolate_keys(kTimes, kPoints, Interpolation::catmull_rom, key)) /
                       h;
    expect_vec_near(before, after, 2e-2f);
  }
  const Vec3 lin_before = (kPoints[1] - interpolate_keys(kTimes, kPoints, Interpolation::linear, 1 - h)) / h;
  const Vec3 lin_after = (interpolate_keys(kTimes, kPoints, Interpolation::linear, 1 + h) - kPoints[1]) / h;
  EXPECT_GT(length(lin_before - lin_after), 1.0f);
}

SceneDesc animated_scene() {
  SceneDesc s;
  s.camera.path = {{0.0f, {0, 0, 5}, {0, 0, 0}}, {2.0f, {2, 0, 5}, {2, 0, 0}}};
  SpotLight spot{{0, 3, 0}, {0, -1, 0}, 0.9f, 0.8f, RGB(1.0f)};
  spot.up = {0, 0, -1};
  spot.gobo.scroll = {0.5f, 0.25f};
  spot.gobo.spin = 1.0f;
  s.lights.push_back(spot);
  s.lights.push_back(BoxLight{{0, 5, 0}, {0, -1, 0}, {0, 0, 1}, 1, 1, 10, RGB(1.0f)});
  s.lights.push_back(DirectionalLight{{0, -1, 0}, RGB(1.0f)});
  s.lights.push_back(PointLight{{1, 1, 1}, RGB(1.0f)});
  LightOptions spot_options;
  spot_options.animation = {{0.0f, Vec3(0, 3, 0), Vec3(0, -1, 0)}, {4.0f, Vec3(4, 3, 0), Vec3(1, 0, 0)}};
  LightOptions box_options;
  box_options.animation = {{1.0f, std::nullopt, Vec3(0, -1, 0)}, {3.0f, std::nullopt, Vec3(0, 0, 1)}};
  LightOptions sun_options;
  sun_options.animation = {{0.0f, std::nullopt, Vec3(0, -1, 0)}, {1.0f, std::nullopt, Vec3(1, 0, 0)}};
  s.light_options = {spot_options, box_options, sun_options};  // the point light has no entry
  VolumePrimitive fog;
  fog.shader.noise = NoiseModulation{1.0f, 0.5f, {1, 0, -2}, {}};
  s.volumes.push_back(fog);
  return s;
}

TEST(SceneAtTime, CameraFollowsItsPathAndTheResultIsStill) {
  const SceneDesc s = animated_scene();
  EXPECT_FLOAT_EQ(s.duration(), 4.0f);
  const SceneDesc at = s.at_time(1.0f);
  expect_vec_near(at.camera.position, {1, 0, 5}, 1e-6f);
  expect_vec_near(at.camera.look_at, {1, 0, 0}, 1e-6f);
  EXPECT_TRUE(at.camera.path.empty());
  for (const LightOptions& o : at.light_options) EXPECT_TRUE(o.animation.empty());
  EXPECT_FLOAT_EQ(at.duration(), 0.0f);
  // Asking a still scene for another time changes nothing.
  const SceneDesc again = at.at_time(3.0f);
  expect_vec_near(again.camera.position, at.camera.position, 0.0f);
  expect_vec_near(std::get<SpotLight>(again.lights[0]).position, std::get<SpotLight>(at.lights[0]).position,
                  0.0f);
  EXPECT_FLOAT_EQ(std::get<SpotLight>(again.lights[0]).gobo.rotation,
                  std::get<SpotLight>(at.lights[0]).gobo.rotation);
}

TEST(SceneAtTime, LightsMoveAndTurnWithUnitDirectionsAndPerpendicularUp) {
  const SceneDesc at = animated_scene().at_time(2.0f);
  const auto& spot = std::get<SpotLight>(at.lights[0]);
  expect_vec_near(spot.position, {2, 3, 0}, 1e-6f);
  // Half-way between -y and +x, renormalised.
  expect_vec_near(spot.direction, normalize(Vec3(1, -1, 0)), 1e-6f);
  EXPECT_NEAR(dot(spot.up, spot.direction), 0.0f, 1e-6f);
  EXPECT_NEAR(length(spot.up), 1.0f, 1e-6f);
  // Gobo velocities folded in: offset = scroll t, rotation = spin t, and no velocity left.
  EXPECT_FLOAT_EQ(spot.gobo.offset.x, 1.0f);
  EXPECT_FLOAT_EQ(spot.gobo.offset.y, 0.5f);
  EXPECT_FLOAT_EQ(spot.gobo.rotation, 2.0f);
  EXPECT_FLOAT_EQ(spot.gobo.spin, 0.0f);

  // The box turns from -y to +z over [1, 3]; its up (+z at the start) stays perpendicular.
  const auto& box = std::get<BoxLight>(at.lights[1]);
  expect_vec_near(box.direction, normalize(Vec3(0, -1, 1)), 1e-6f);
  expect_vec_near(box.position, {0, 5, 0}, 0.0f);  // no position keys: stays
  EXPECT_NEAR(dot(box.up, box.direction), 0.0f, 1e-6f);
  EXPECT_GT(box.up.z, 0.0f);

  const auto& sun = std::get<DirectionalLight>(at.lights[2]);
  expect_vec_near(sun.direction, {1, 0, 0}, 1e-6f);  // after its last key
  expect_vec_near(std::get<PointLight>(at.lights[3]).position, {1, 1, 1}, 0.0f);
}

TEST(SceneAtTime, NoiseMovesWithTheWind) {
  const SceneDesc at = animated_scene().at_time(1.5f);
  const NoiseModulation& n = *at.volumes[0].shader.noise;
  expect_vec_near(n.offset, {1.5f, 0, -3}, 1e-6f);
  expect_vec_near(n.wind, {}, 0.0f);
}

TEST(SceneAtTime, BeforeTheFirstKeyTheLightHoldsTheFirstKey) {
  const SceneDesc at = animated_scene().at_time(0.0f);  // kept: the light is a reference into it
  const auto& box = std::get<BoxLight>(at.lights[1]);
  expect_vec_near(box.direction, {0, -1, 0}, 1e-6f);
}

}  // namespace
}  // namespace caligo
