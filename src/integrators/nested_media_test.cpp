// Nested dielectrics in the production path tracer (media/medium_stack.h): the seed's
// overlapping cubes as pixel tests, IOR ratios at interfaces, the camera's starting stack, shadow
// rays through priority media, and neutrality where no priority surface is met.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>

#include "integrators/interface_eta.h"
#include "integrators/path_tracer.h"
#include "integrators/visibility.h"
#include "integrators/test_scenes.h"
#include "render/render.h"

namespace caligo {
namespace {

using testing::camera_at;

int add_medium(SceneDesc& desc, const char* name, RGB sigma_a, RGB sigma_s = RGB(0.0f)) {
  desc.media.push_back({name, VolumeShader{sigma_a, sigma_s}});
  return int(desc.media.size()) - 1;
}

// A null (interface-free) or dielectric material bounding `interior` (-1: vacuum).
int add_boundary(SceneDesc& desc, const char* name, int priority, int interior, float ior = 1.0f,
                 bool dielectric = false) {
  Material m;
  m.name = name;
  m.bsdf = dielectric ? Bsdf{DielectricBsdf{ior}} : Bsdf{NullBsdf{}};
  m.priority = priority;
  m.interior = interior;
  m.ior = ior;
  desc.materials.push_back(m);
  return int(desc.materials.size()) - 1;
}

void add_box(SceneDesc& desc, Vec3 lo, Vec3 hi, int material) {
  ShapeDesc s;
  s.geometry = BoxShape{lo, hi};
  s.material = material;
  desc.shapes.push_back(s);
}

Image render_desc(const SceneDesc& desc, int spp) {
  const auto scene = Scene::build(desc);
  RenderSettings s = render_settings(desc);
  s.spp = spp;
  return render(*scene, s).image;
}

// ---- the seed's cubes ----

constexpr RGB kRed{0.1f, 1.0f, 1.0f};    // sigma_a: passes red
constexpr RGB kGreen{1.0f, 0.1f, 1.0f};  // passes green

// Red [0, 2] and green [1, 3] along x, seen end-on under a white sky through a 0.5 degree
// field: every camera ray crosses 1 m of red alone, 1 m of the overlap and 1 m of green alone
// (to 2e-5), so the image's expected value is exp(-sum sigma_i L_i) with the lengths the rules
// give each medium. The path tracer estimates absorption by free-flight sampling (a path passes
// with probability mean_c T_c, then carries T / mean T), so the mean of 9 x 2^14 paths has a
// relative standard error of at most sqrt((1 - p) / (p N)) = 0.9 % for p >= 0.15.
constexpr int kCubeSpp = 1 << 14;

RGB cubes_pixel(int red_priority, int green_priority) {
  SceneDesc desc = camera_at({-5, 0, 0}, {10, 0, 0}, {3, 3}, 0.5f);
  const int red = add_boundary(desc, "red", red_priority, add_medium(desc, "red", kRed));
  const int green = add_boundary(desc, "green", green_priority, add_medium(desc, "green", kGreen));
  add_box(desc, {0, -0.5f, -0.5f}, {2, 0.5f, 0.5f}, red);
  add_box(desc, {1, -0.45f, -0.45f}, {3, 0.45f, 0.45f}, green);
  desc.lights.push_back(EnvironmentLight{RGB(1.0f)});
  const Image image = render_desc(desc, kCubeSpp);
  RGB sum(0.0f);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 3; ++x) sum += image.rgb(x, y, 0);
  return sum * (1.0f / 9.0f);
}

RGB expected(float red_length, float green_length) {
  return {std::exp(-(kRed.r * red_length + kGreen.r * green_length)),
          std::exp(-(kRed.g * red_length + kGreen.g * green_length)),
          std::exp(-(kRed.b * red_length + kGreen.b * green_length))};
}

// Within 4 standard errors of the free-flight estimate (see above), per channel.
void expect_rgb(RGB got, RGB want, const char* what) {
  const double n = 9.0 * kCubeSpp, p = std::max(0.05f, want.average());
  for (int c = 0; c < 3; ++c) {
    const double se = want[c] / p * std::sqrt(p * (1 - p) / n);
    EXPECT_NEAR(got[c], want[c], 4.0 * se + 1e-6) << what << " channel " << c;
  }
}

TEST(NestedMedia, RedHigherIsVisibleInsideGreenAndGreenInvisibleInsideRed) {
  // The overlap is red's: 2 m of red, then 1 m of green.
  expect_rgb(cubes_pixel(kPriorityHigh, kPriorityNormal), expected(2, 1), "red higher");
}

TEST(NestedMedia, GreenHigherIsVisibleInsideRedAndRedInvisibleInsideGreen) {
  expect_rgb(cubes_pixel(kPriorityNormal, kPriorityHigh), expected(1, 2), "green higher");
}

TEST(NestedMedia, EqualPrioritiesMergeWithNoInteriorHits) {
  // Merged: entered through red, the ray keeps red's medium through the overlap and, leaving
  // red while still in green, on to green's far face.
  expect_rgb(cubes_pixel(kPriorityNormal, kPriorityNormal), expected(3, 0), "equal");
}

TEST(NestedMedia, OffBoundariesCarryNoMedium) {
  // Priority Off null surfaces are crossed as before: neither interior applies.
  expect_rgb(cubes_pixel(kPriorityOff, kPriorityOff), RGB(1.0f), "off");
}

// ---- IOR ratios ----

TEST(NestedMedia, InterfaceEtaUsesTheMediaOnEitherSide) {
  const MediumEntry glass{1, kPriorityHigh, {-1, 1.5f}}, liquid{2, kPriorityNormal, {0, 1.33f}};
  MediumStack stack;
  // Air -> glass, arriving on the glass's front face: n_inside / n_outside = 1.5 / 1.
  EXPECT_FLOAT_EQ(interface_eta(stack, glass, 1.5f, true), 1.5f);
  stack.cross(glass);
  stack.cross(liquid);  // inside the wall: a false hit
  // Glass -> liquid through the glass's inner face, from the back side: inside (glass) 1.5 over
  // outside (liquid) 1.33. Air never comes in.
  EXPECT_FLOAT_EQ(interface_eta(stack, glass, 1.5f, false), 1.5f / 1.33f);
  stack.cross(glass);
  // Liquid -> air through the free surface, from inside: 1.33 / 1.
  EXPECT_FLOAT_EQ(interface_eta(stack, liquid, 1.33f, false), 1.33f);
  // An Off glass sphere under water refracts against the water.
  EXPECT_FLOAT_EQ(interface_eta(stack, std::nullopt, 1.5f, true), 1.5f / 1.33f);
  stack.cross(liquid);
  EXPECT_TRUE(stack.empty());
  EXPECT_FLOAT_EQ(interface_eta(stack, std::nullopt, 1.5f, true), 1.5f);  // bit for bit as before
}

// The reflectance at an interface tells which IOR ratio a path used. A camera inside a glass
// block looks straight down at its bottom face, where a deep, black water volume (modelled
// overlapping the glass by 0.1 m, lower priority) lies below: glass -> water reflects
// R1 = ((1.5 - 1.33) / (1.5 + 1.33))^2 = 0.36 %, which travels up and out through the top
// (glass -> air, R2 = 4 %) to a white sky: L = n^2 R1 (1 - R2) / (1 - R1 R2), where n^2 = 2.25 is
// the radiance gain of light entering glass (L / n^2 is invariant). An air gap between the two
// would reflect 4 % instead, ten times more.
TEST(NestedMedia, GlassToWaterReflectsWithTheirIorRatio) {
  SceneDesc desc = camera_at({0, 0, 0}, {0, -5, 0.001f}, {1, 1}, 0.2f);
  const int glass = add_boundary(desc, "glass", kPriorityHigh, -1, 1.5f, true);
  const int water =
      add_boundary(desc, "water", kPriorityNormal, add_medium(desc, "ink", RGB(50.0f)), 1.33f, true);
  add_box(desc, {-50, -0.5f, -50}, {50, 0.5f, 50}, glass);
  add_box(desc, {-50, -20, -50}, {50, -0.4f, 50}, water);
  desc.lights.push_back(EnvironmentLight{RGB(1.0f)});
  desc.render.path.limits.max_bounces = 16;
  const auto scene = Scene::build(desc);
  ASSERT_EQ(scene->camera_stack().size(), 1u);  // the camera is in the glass
  const int spp = 1 << 18;
  const float got = render_desc(desc, spp).rgb(0, 0, 0).average();
  const double r1 = std::pow((1.5 - 1.33) / (1.5 + 1.33), 2), r2 = 0.04;
  const double want = 2.25 * r1 * (1 - r2) / (1 - r1 * r2);
  // Each path reflects at the bottom with probability ~R1 and then carries ~2.25: a Bernoulli
  // estimate, standard error 2.25 sqrt(R1 (1 - R1) / spp) = 2.7e-4 (3.4 % of the value).
  const double se = 2.25 * std::sqrt(r1 * (1 - r1) / spp);
  std::printf("glass -> water: %.5f, expected %.5f (se %.5f); through an air gap it would be %.5f\n", got, want, se,
              2.25 * 0.04 * 0.96 / (1 - 0.04 * 0.04));
  EXPECT_NEAR(got, want, 4.0 * se);
}

// ---- the camera's starting stack ----

TEST(NestedMedia, CameraProbeFindsTheMediaAroundIt) {
  SceneDesc desc = camera_at({0, -1, 0}, {0, -1, -5}, {4, 4}, 40.0f);
  const int water_medium = add_medium(desc, "water", RGB(0.1f));
  const int water = add_boundary(desc, "water", kPriorityNormal, water_medium, 1.33f, true);
  ShapeDesc plane;  // an open water surface, normal up
  plane.geometry = RectangleShape{{-10, 0, -10}, {0, 0, 20}, {20, 0, 0}};
  plane.material = water;
  desc.shapes.push_back(plane);
  const int clip = add_boundary(desc, "clip", kPriorityVeryHigh, -1);
  add_box(desc, {2, -0.5f, -0.5f}, {3, 0.5f, 0.5f}, clip);
  const auto scene = Scene::build(desc);
  const uint32_t plane_id = 0, clip_id = 1;
  // Under the open plane: in water.
  EXPECT_EQ(scene->camera_stack().size(), 1u);
  EXPECT_TRUE(scene->camera_stack().contains(plane_id));
  EXPECT_EQ(scene->camera_stack().current().medium, 0);
  EXPECT_FLOAT_EQ(scene->camera_stack().current().ior, 1.33f);
  // Above it: nothing.
  EXPECT_TRUE(scene->stack_at({0, 1, 0}).empty());
  // In the clip box straddling the surface, below the water line: water and the box, and the
  // box (higher) decides: vacuum.
  const MediumStack split = scene->stack_at({2.5f, -0.2f, 0});
  EXPECT_EQ(split.size(), 2u);
  EXPECT_TRUE(split.contains(plane_id) && split.contains(clip_id));
  EXPECT_EQ(split.current().medium, -1);
  // In the box above the water line: the box alone.
  const MediumStack above = scene->stack_at({2.5f, 0.2f, 0});
  EXPECT_EQ(above.size(), 1u);
  EXPECT_TRUE(above.contains(clip_id));
  // Outside the box's x range, above water: empty; inside a closed sphere: the sphere.
  SceneDesc closed = camera_at({0, 0, 0}, {0, 0, -5}, {4, 4}, 40.0f);
  const int ball = add_boundary(closed, "ball", kPriorityNormal, add_medium(closed, "m", RGB(1.0f)), 1.4f, true);
  ShapeDesc sphere;
  sphere.geometry = SphereShape{{0, 0, 0}, 2.0f};
  sphere.material = ball;
  closed.shapes.push_back(sphere);
  const auto inside = Scene::build(closed);
  EXPECT_EQ(inside->camera_stack().size(), 1u);
  EXPECT_EQ(inside->camera_stack().current().medium, 0);
  EXPECT_TRUE(inside->stack_at({0, 3, 0}).empty());
}

// A camera under the water plane looks up through 0.5 m of water at the sky. Checks that the
// probe feeds camera paths: without it the camera ray would start in vacuum and the water would
// vanish. Free-flight estimate of p = e^{-0.1} from 2^16 paths: standard error 1.1e-3.
TEST(NestedMedia, CameraUnderOpenWaterSeesThroughTheWater) {
  SceneDesc desc = camera_at({0, -0.5f, 0}, {0, -0.5f, -5}, {1, 1}, 0.5f);
  const int water = add_boundary(desc, "water", kPriorityNormal, add_medium(desc, "water", RGB(0.2f)), 1.0f);
  ShapeDesc plane;
  plane.geometry = RectangleShape{{-50, 0, -50}, {0, 0, 100}, {100, 0, 0}};
  plane.material = water;
  desc.shapes.push_back(plane);
  desc.lights.push_back(EnvironmentLight{RGB(1.0f)});
  // The ray runs horizontally under water to infinity: fully absorbed.
  EXPECT_EQ(render_desc(desc, 64).rgb(0, 0, 0).average(), 0.0f);
  // Looking up through 0.5 m of water at the sky: e^{-0.1}.
  desc.camera.look_at = {0, 5, -0.001f};
  const double p = std::exp(-0.2 * 0.5), se = std::sqrt(p * (1 - p) / 65536.0);
  EXPECT_NEAR(render_desc(desc, 65536).rgb(0, 0, 0).average(), p, 4.0 * se);
}

// ---- shadow rays ----

// A point light 1 m outside an absorbing box (x in [-1, 1]); the shadow ray from a point inside
// the box at x = -0.5 crosses 1.5 m of its medium. The same line seen by a camera ray gives the
// same exp(-sigma L).
TEST(NestedMedia, ShadowRaysSeeTheMediaTheCameraSees) {
  for (bool dielectric : {false, true}) {
    SceneDesc desc = camera_at({-0.5f, 0, 0}, {10, 0, 0}, {1, 1}, 0.2f);
    desc.render.path.priority_shadows = true;
    const RGB sigma{0.4f, 0.2f, 0.1f};
    const int box = add_boundary(desc, "box", kPriorityNormal, add_medium(desc, "m", sigma), 1.0f, dielectric);
    add_box(desc, {-1, -1, -1}, {1, 1, 1}, box);
    desc.lights.push_back(PointLight{{2, 0, 0}, RGB(1.0f)});
    const auto scene = Scene::build(desc);
    PathScratch scratch;
    scratch.stack.assign(scene->stack_at({-0.5f, 0, 0}));
    ASSERT_EQ(scratch.stack.current().medium, 0);
    PathCounters counters;
    const Vec3 x{-0.5f, 0, 0};
    const auto ls = sample_light(scene->lights()[0], x, {0.5f, 0.5f});
    ASSERT_TRUE(ls);
    ShadowMedium passing(0.5f);
    passing.priority_shadows = true;
    const RGB tr = light_transmittance(*scene, x, x, *ls, true, passing, scratch, counters);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(tr[c], std::exp(-sigma[c] * 1.5f), 1e-5f) << "dielectric " << dielectric;
    // With priority_shadows off a dielectric boundary blocks; a null one never does.
    const RGB tr2 = light_transmittance(*scene, x, x, *ls, true, ShadowMedium(0.5f), scratch, counters);
    EXPECT_EQ(tr2.is_black(), dielectric);
    // The camera ray from inside, out through the box's face to the sky: exp(-sigma 1.5) too
    // (free-flight estimate from 2^16 paths; pass probability p = mean T = 0.72, so the relative
    // standard error is sqrt((1 - p) / (p N)) = 0.24 %).
    desc.lights = {EnvironmentLight{RGB(1.0f)}};
    if (!dielectric) {
      const RGB seen = render_desc(desc, 65536).rgb(0, 0, 0);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(seen[c], std::exp(-sigma[c] * 1.5f), 4 * 0.0024 * seen[c]);
    }
  }
}

// Only a REAL dielectric crossing takes a light sample out of MIS (weight 1): inside a clipping
// box (very high, vacuum) the water surface is a hidden crossing, straight for BSDF samples too.
TEST(NestedMedia, HiddenDielectricCrossingsKeepMis) {
  SceneDesc desc = camera_at({0, 3, 5}, {0, 0, 0}, {1, 1}, 30.0f);
  desc.render.path.priority_shadows = true;
  const int water = add_boundary(desc, "water", kPriorityNormal, add_medium(desc, "w", RGB(0.1f)), 1.33f, true);
  add_box(desc, {-10, -10, -10}, {10, 0, 10}, water);
  const int clip = add_boundary(desc, "clip", kPriorityVeryHigh, -1);
  add_box(desc, {-1, -1, -1}, {1, 1, 1}, clip);
  const auto scene = Scene::build(desc);
  PathScratch scratch;
  PathCounters counters;
  // Whether the shadow ray from x to a point light at `light` crosses a dielectric for real.
  const auto through = [&](Vec3 x, Vec3 light) {
    scratch.stack.assign(scene->stack_at(x));
    scratch.pending.clear();
    const LightSample ls{RGB(1.0f), normalize(light - x), distance(light, x), 1.0f, true};
    bool crossed = false;
    ShadowMedium passing(0.5f);
    passing.priority_shadows = true;
    const RGB tr = light_transmittance(*scene, x, x, ls, true, passing, scratch, counters, kInfinity, &crossed);
    EXPECT_FALSE(tr.is_black());
    return crossed;
  };
  EXPECT_FALSE(through({0, -0.5f, 0}, {0, 0.5f, 0}));  // both in the box: the water surface is hidden
  EXPECT_TRUE(through({3, -1.0f, 0}, {3, 2.0f, 0}));    // outside it: water -> air is a real interface
}

// ---- neutrality ----

// Priority surfaces that no ray meets switch the nested code path on without changing any
// answer: the image is identical bit for bit to the scene without them.
TEST(NestedMedia, UnmetPriorityObjectsChangeNothing) {
  SceneDesc desc = camera_at({0, 1, 4}, {0, 0.5f, 0}, {24, 18}, 40.0f);
  Material diffuse;
  diffuse.name = "white";
  diffuse.bsdf = DiffuseBsdf{RGB(0.7f)};
  desc.materials.push_back(diffuse);
  Material glass;
  glass.name = "glass";
  glass.bsdf = DielectricBsdf{1.5f};
  glass.ior = 1.5f;
  desc.materials.push_back(glass);
  add_box(desc, {-3, -0.1f, -3}, {3, 0, 3}, 0);
  ShapeDesc ball;
  ball.geometry = SphereShape{{0, 0.5f, 0}, 0.5f};
  ball.material = 1;
  desc.shapes.push_back(ball);
  VolumePrimitive fog{SphereVolumeShape{Sphere::make({0.5f, 0.5f, 0.5f}, 1.0f, {})}, {RGB(0.05f), RGB(0.3f)}};
  desc.volumes.push_back(fog);
  desc.lights.push_back(PointLight{{1, 3, 1}, RGB(10.0f)});
  desc.lights.push_back(EnvironmentLight{RGB(0.2f)});
  const Image plain = render_desc(desc, 8);
  // Inside the ground slab, where no ray goes (and within the scene's bounds, which set the
  // environment's share of light selection): a priority medium box.
  const int hidden = add_boundary(desc, "hidden", kPriorityNormal, add_medium(desc, "hidden", RGB(1.0f)));
  add_box(desc, {-2.9f, -0.09f, -2.9f}, {-2.5f, -0.01f, -2.5f}, hidden);
  ASSERT_TRUE(Scene::build(desc)->has_priority_objects());
  const Image nested = render_desc(desc, 8);
  ASSERT_EQ(plain.pixels().size(), nested.pixels().size());
  EXPECT_EQ(std::memcmp(plain.pixels().data(), nested.pixels().data(), plain.pixels().size() * sizeof(float)), 0);
}

}  // namespace
}  // namespace caligo
