// The nested-dielectric built-ins, built: their priorities, interiors and the media around the
// camera (Scene::camera_stack()).
#include <gtest/gtest.h>

#include <algorithm>

#include "scene/builtins.h"
#include "scene/scene.h"

namespace caligo {
namespace {

const Material& material(const SceneDesc& s, const std::string& name) {
  const auto it = std::find_if(s.materials.begin(), s.materials.end(),
                               [&](const Material& m) { return m.name == name; });
  if (it == s.materials.end()) throw std::runtime_error("no material " + name);
  return *it;
}

std::string interior_name(const SceneDesc& s, const Material& m) {
  return m.interior < 0 ? "" : s.media[size_t(m.interior)].name;
}

SceneDesc load(const char* name) {
  const BuiltinScene* b = find_builtin(name);
  if (!b) throw std::runtime_error(std::string("no builtin ") + name);
  return parse_builtin(*b);
}

TEST(NestedDielectricBuiltins, EveryOneBuildsAndIsSmall) {
  for (const char* name :
       {"priority-cubes", "glass-of-water", "underwater", "underwater-above", "underwater-split", "sss"}) {
    SCOPED_TRACE(name);
    const SceneDesc desc = load(name);
    EXPECT_LE(desc.camera.resolution.x * desc.camera.resolution.y, 256 * 256);
    EXPECT_LE(desc.render.spp, 64);
    const auto scene = Scene::build(desc);
    EXPECT_TRUE(scene->has_priority_objects());
  }
}

TEST(NestedDielectricBuiltins, PriorityCubes) {
  const SceneDesc s = load("priority-cubes");
  const Material& red = material(s, "red");
  const Material& green = material(s, "green");
  EXPECT_TRUE(std::holds_alternative<NullBsdf>(red.bsdf));
  EXPECT_TRUE(std::holds_alternative<NullBsdf>(green.bsdf));
  EXPECT_EQ(red.priority, kPriorityHigh);
  EXPECT_EQ(green.priority, kPriorityNormal);
  EXPECT_EQ(interior_name(s, red), "red");
  EXPECT_EQ(interior_name(s, green), "green");
  const RGB r = s.media[size_t(red.interior)].shader.sigma_a;
  EXPECT_LT(r[0], r[1]);  // red passes red
  const RGB g = s.media[size_t(green.interior)].shader.sigma_a;
  EXPECT_LT(g[1], g[0]);  // green passes green
  EXPECT_TRUE(Scene::build(s)->camera_stack().empty());
}

TEST(NestedDielectricBuiltins, GlassOfWater) {
  const SceneDesc s = load("glass-of-water");
  const Material& glass = material(s, "glass");
  const Material& water = material(s, "water");
  const Material& ice = material(s, "ice");
  EXPECT_FLOAT_EQ(glass.ior, 1.5f);
  EXPECT_EQ(glass.priority, kPriorityHigh);
  EXPECT_EQ(glass.interior, -1);
  EXPECT_FLOAT_EQ(water.ior, 1.33f);
  EXPECT_EQ(water.priority, kPriorityNormal);
  EXPECT_EQ(interior_name(s, water), "water");
  EXPECT_FLOAT_EQ(ice.ior, 1.31f);
  EXPECT_EQ(ice.priority, kPriorityVeryHigh);
  EXPECT_EQ(interior_name(s, ice), "ice");
  EXPECT_GT(s.media[size_t(ice.interior)].shader.sigma_s[0], 0.0f);
  // The water box overlaps the glass walls: it reaches past their inner faces.
  const ShapeDesc* water_box = nullptr;
  for (const ShapeDesc& shape : s.shapes)
    if (s.materials[size_t(shape.material)].name == "water") water_box = &shape;
  ASSERT_NE(water_box, nullptr);
  EXPECT_GT(std::get<BoxShape>(water_box->geometry).max.x, 0.036f);
  EXPECT_TRUE(Scene::build(s)->camera_stack().empty());
}

TEST(NestedDielectricBuiltins, UnderwaterCameraStacks) {
  {
    const SceneDesc s = load("underwater");
    const Material& water = material(s, "water");
    EXPECT_EQ(water.priority, kPriorityNormal);
    EXPECT_FLOAT_EQ(water.ior, 1.33f);
    EXPECT_EQ(interior_name(s, water), "pool");
    EXPECT_TRUE(s.render.path.priority_shadows);
    EXPECT_LT(s.camera.position.y, 0.0f);
    const auto scene = Scene::build(s);
    const MediumStack& stack = scene->camera_stack();
    ASSERT_EQ(stack.size(), 1u);
    EXPECT_EQ(stack.entries()[0].priority, kPriorityNormal);
    EXPECT_GE(stack.current().medium, 0);  // in the pool's water
    EXPECT_FLOAT_EQ(stack.current().ior, 1.33f);
  }
  {
    const SceneDesc s = load("underwater-above");
    EXPECT_GT(s.camera.position.y, 0.0f);
    EXPECT_TRUE(Scene::build(s)->camera_stack().empty());
  }
  {
    const SceneDesc s = load("underwater-split");
    const Material& clip = material(s, "clip");
    EXPECT_TRUE(std::holds_alternative<NullBsdf>(clip.bsdf));
    EXPECT_EQ(clip.priority, kPriorityVeryHigh);
    EXPECT_EQ(clip.interior, -1);
    EXPECT_LT(s.camera.position.y, 0.0f);
    EXPECT_GT(s.camera.position.y, -0.05f);  // just below the water line
    const auto scene = Scene::build(s);
    const MediumStack& stack = scene->camera_stack();
    ASSERT_EQ(stack.size(), 2u);  // the water and the clipping box
    std::vector<int> priorities;
    for (const MediumEntry& e : stack.entries()) priorities.push_back(e.priority);
    std::sort(priorities.begin(), priorities.end());
    EXPECT_EQ(priorities, (std::vector<int>{kPriorityVeryHigh, kPriorityNormal}));
    EXPECT_EQ(stack.current(), (MediumState{-1, 1.0f}));  // the box's vacuum wins
  }
}

TEST(NestedDielectricBuiltins, SssDuck) {
  const SceneDesc s = load("sss");
  const Material& wax = material(s, "wax");
  EXPECT_FLOAT_EQ(wax.ior, 1.4f);
  EXPECT_EQ(wax.priority, kPriorityNormal);
  const VolumeShader& medium = s.media[size_t(wax.interior)].shader;
  const RGB extinction = medium.sigma_a + medium.sigma_s;
  for (int c = 0; c < 3; ++c) {
    EXPECT_GE(extinction[c], 20.0f);
    EXPECT_LE(extinction[c], 60.0f);
    EXPECT_GE(medium.sigma_s[c] / extinction[c], 0.89f);
  }
  EXPECT_TRUE(std::holds_alternative<MeshFileShape>(s.shapes[1].geometry));
  EXPECT_TRUE(Scene::build(s)->camera_stack().empty());
}

}  // namespace
}  // namespace caligo

namespace caligo {
namespace {

// `slab`: the optical depth along every pixel-centre camera ray, from the boxes' chords, is
// 0 or one box's thickness times sigma_a, by pixel column: the documented exact answers
// 1, e^-0.5, e^-1, e^-2 need nothing else (no surfaces, one uniform sky of radiance 1).
TEST(CameraBuiltins, SlabPixelsSeeOneThicknessEach) {
  const SceneDesc s = parse_builtin(*find_builtin("slab"));
  EXPECT_EQ(s.camera.projection, CameraProjection::orthographic);
  EXPECT_TRUE(s.shapes.empty());
  ASSERT_EQ(s.lights.size(), 1u);
  const auto& sky = std::get<EnvironmentLight>(s.lights[0]);
  EXPECT_EQ(sky.radiance.r, 1.0f);
  ASSERT_EQ(s.volumes.size(), 3u);
  const Camera camera(s.camera, s.camera.resolution);
  for (const VolumePrimitive& v : s.volumes) {
    EXPECT_TRUE(v.shader.sigma_s.is_black());
    EXPECT_EQ(v.shader.sigma_a.g, 1.0f);
  }
  const float thickness[3] = {0.5f, 1.0f, 2.0f};
  for (int y = 0; y < s.camera.resolution.y; ++y)
    for (int x = 0; x < s.camera.resolution.x; ++x) {
      const Ray ray = camera.generate_ray({float(x) + 0.5f, float(y) + 0.5f});
      float depth = 0.0f;
      for (const VolumePrimitive& v : s.volumes)
        if (auto t = volume_hull_interval(v.shape, ray)) depth += (t->t1 - t->t0) * v.shader.sigma_a.g;
      const bool row_in = y >= 8 && y < 24;
      const int box = x >= 4 && x < 28 ? 0 : (x >= 36 && x < 60 ? 1 : (x >= 68 && x < 92 ? 2 : -1));
      const float expected = row_in && box >= 0 ? thickness[box] : 0.0f;
      EXPECT_NEAR(depth, expected, 1e-5f) << x << "," << y;
    }
}

TEST(CameraBuiltins, DofIsAThinLensFocusedOnTheShaft) {
  const SceneDesc s = parse_builtin(*find_builtin("dof"));
  const Camera camera(s.camera, s.camera.resolution);
  EXPECT_TRUE(camera.has_aperture());
  EXPECT_FLOAT_EQ(camera.aperture_radius(), 0.1f);
  // The occluding sphere at (0.2, 2.2, 0), in the middle of the shaft, is in focus.
  EXPECT_NEAR(dot(Vec3(0.2f, 2.2f, 0.0f) - camera.position(), camera.forward()), camera.focus_distance(), 0.1f);
  EXPECT_FALSE(s.volumes.empty());
}

}  // namespace
}  // namespace caligo
