#include "scene/scene.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "geometry/mesh_generate.h"

namespace caligo {
namespace {

SceneDesc base() {
  SceneDesc desc;
  desc.file = "test.json";
  desc.materials.push_back({"white", DiffuseBsdf{RGB(0.5f)}, {}, false});
  desc.materials.push_back({"lamp", BlackBsdf{}, RGB(4.0f), false});
  return desc;
}

TEST(Scene, EmissiveShapesBecomeLightsAndHitsMapBack) {
  SceneDesc desc = base();
  desc.shapes.push_back({BoxShape{{-1, -1, -1}, {1, 1, 1}}, {}, 1, {"test.json", "/shapes/0"}});
  desc.shapes.push_back({SphereShape{{5, 0, 0}, 0.5f}, Transform::scale(Vec3(2.0f)), 1, {}});
  desc.lights.push_back(QuadLight{{-1, 3, -1}, {2, 0, 0}, {0, 0, 2}, RGB(1.0f)});
  const auto scene = Scene::build(desc);
  // One quad light, 12 box triangles, one sphere.
  ASSERT_EQ(scene->lights().size(), 14u);
  const auto* sphere = std::get_if<SphereLight>(&scene->lights().back());
  ASSERT_NE(sphere, nullptr);
  EXPECT_NEAR(sphere->radius, 1.0f, 1e-6f);
  EXPECT_NEAR(sphere->center.x, 10.0f, 1e-5f);

  const Ray ray{{0, 0, -5}, {0, 0, 1}};
  const auto hit = scene->surfaces().intersect(ray);
  ASSERT_TRUE(hit);
  const SurfaceInteraction si = scene->interaction(ray, *hit);
  EXPECT_EQ(si.material->name, "lamp");
  ASSERT_GE(si.light, 1);
  EXPECT_TRUE(std::holds_alternative<TriangleLight>(scene->lights()[size_t(si.light)]));

  // The quad light is visible geometry too.
  const Ray up{{0, 0, 0.0f}, {0, 1, 0}, 1.1f};
  const auto quad_hit = scene->surfaces().intersect(up);
  ASSERT_TRUE(quad_hit);
  EXPECT_EQ(scene->interaction(up, *quad_hit).light, 0);
}

TEST(Scene, LightSelectionFollowsPower) {
  SceneDesc desc = base();
  desc.lights.push_back(PointLight{{0, 1, 0}, RGB(1.0f)});
  desc.lights.push_back(PointLight{{0, 2, 0}, RGB(3.0f)});
  const auto scene = Scene::build(desc);
  const LightSampler& by_power = scene->light_sampler(LightSamplerKind::kPower);
  EXPECT_NEAR(by_power.pmf({}, {}, 0), 0.25f, 1e-6f);
  EXPECT_NEAR(by_power.pmf({}, {}, 1), 0.75f, 1e-6f);
}

TEST(Scene, NonUniformlyScaledEmissiveSphereIsAnInputError) {
  SceneDesc desc = base();
  desc.shapes.push_back(
      {SphereShape{{0, 0, 0}, 1.0f}, Transform::scale({1, 2, 1}), 1, {"test.json", "/shapes/0"}});
  try {
    Scene::build(desc);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().json_path, "/shapes/0");
    EXPECT_NE(std::string(e.what()).find("uniformly"), std::string::npos);
  }
}

TEST(Scene, MissingMeshFileIsAnInputErrorAtTheShape) {
  SceneDesc desc = base();
  desc.shapes.push_back({MeshFileShape{"/nonexistent/bunny.obj"}, {}, 0, {"room.json", "/shapes/3"}});
  try {
    Scene::build(desc);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("room.json: /shapes/3"), std::string::npos) << what;
    EXPECT_NE(what.find("bunny.obj"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace caligo

namespace caligo {
namespace {

// A generated occluder is a real, closed mesh in the scene: a ray through the knot's tube
// hits it, one beside it does not.
TEST(Scene, GeneratedMeshesBecomeSurfaces) {
  SceneDesc desc = base();
  desc.shapes.push_back({GeneratedMeshShape{GeneratedMeshShape::Kind::kTorusKnot, 30000}, {}, 0, {}});
  desc.shapes.push_back(
      {GeneratedMeshShape{GeneratedMeshShape::Kind::kSphere, 20000}, Transform::translate({0, 0, -20}), 0, {}});
  const auto scene = Scene::build(desc);
  const TorusKnot k = torus_knot_for(30000);
  EXPECT_GE(2 * k.segments * k.sides, 30000);
  // The (2, 3) knot passes through (major + minor, 0, 0) = (1.4, 0, 0) at s = 0 with a tangent
  // in the y-z plane: a ray along -x meets the tube (radius 0.15) square on, at x = 1.55.
  const auto hit = scene->surfaces().intersect(Ray{{5.0f, 0.0f, 0.0f}, {-1, 0, 0}});
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 5.0f - 1.55f, 0.01f);
  // The sphere 20 m away along -z, radius 1.
  const auto far = scene->surfaces().intersect(Ray{{0.0f, 0.0f, -10.0f}, {0, 0, -1}});
  ASSERT_TRUE(far);
  EXPECT_NEAR(far->t, 9.0f, 0.01f);
}

}  // namespace
}  // namespace caligo
