#include "scene/builtins.h"

#include <gtest/gtest.h>

#include <set>

#include "lights/gobo.h"
#include "settings/aov.h"

namespace caligo {
namespace {

TEST(Builtins, EveryBuiltinParses) {
  const auto scenes = builtin_scenes();
  ASSERT_FALSE(scenes.empty());
  for (const BuiltinScene& b : scenes) {
    SCOPED_TRACE(b.name);
    EXPECT_FALSE(b.description.empty());
    const SceneDesc scene = parse_builtin(b);
    EXPECT_EQ(scene.file, "builtin:" + b.name);
  }
}

TEST(Builtins, NamesAreUniqueAndFindable) {
  std::set<std::string> names;
  for (const BuiltinScene& b : builtin_scenes()) {
    EXPECT_TRUE(names.insert(b.name).second) << "duplicate builtin " << b.name;
    const BuiltinScene* found = find_builtin(b.name);
    ASSERT_NE(found, nullptr);
    EXPECT_EQ(found->name, b.name);
    EXPECT_EQ(found->json, b.json);
  }
  for (const char* required : {"default", "furnace", "point-in-sphere", "lights-showcase"})
    EXPECT_TRUE(names.count(required)) << required;
  EXPECT_EQ(builtin_scenes().front().name, "default");
}

TEST(Builtins, UnknownNameIsNull) {
  EXPECT_EQ(find_builtin("no-such-scene"), nullptr);
  EXPECT_EQ(find_builtin(""), nullptr);
}

// The analytic scenes must stay what the integrator tests assume.
TEST(Builtins, FurnaceIsAClosedEmittingSphereAroundTheCamera) {
  const SceneDesc scene = parse_builtin(*find_builtin("furnace"));
  ASSERT_EQ(scene.shapes.size(), 1u);
  const auto& sphere = std::get<SphereShape>(scene.shapes[0].geometry);
  EXPECT_LT(distance(scene.camera.position, sphere.center), sphere.radius);
  const Material& wall = scene.materials[scene.shapes[0].material];
  EXPECT_EQ(std::get<DiffuseBsdf>(wall.bsdf).reflectance, RGB(0.5f));
  EXPECT_EQ(wall.emission, RGB(1.0f));
  EXPECT_TRUE(wall.two_sided_emission);
  EXPECT_TRUE(scene.lights.empty());
  EXPECT_EQ(scene.camera.resolution, (Vec2i{32, 32}));
  EXPECT_GE(scene.render.path.limits.max_bounces, 1000);
}

TEST(Builtins, PointInSphereHasTheLightAtTheCentre) {
  const SceneDesc scene = parse_builtin(*find_builtin("point-in-sphere"));
  ASSERT_EQ(scene.shapes.size(), 1u);
  const auto& sphere = std::get<SphereShape>(scene.shapes[0].geometry);
  EXPECT_FLOAT_EQ(sphere.radius, 2.0f);
  EXPECT_LT(distance(scene.camera.position, sphere.center), sphere.radius);
  EXPECT_EQ(std::get<DiffuseBsdf>(scene.materials[scene.shapes[0].material].bsdf).reflectance, RGB(0.5f));
  ASSERT_EQ(scene.lights.size(), 1u);
  const auto& point = std::get<PointLight>(scene.lights[0]);
  EXPECT_EQ(point.position, sphere.center);
  EXPECT_EQ(point.intensity, RGB(4.0f));
  EXPECT_EQ(scene.camera.resolution, (Vec2i{32, 32}));
}

// The compositing scene: held-out plate objects around a fog bank, one CG object, an invisible
// sky (so every pixel's alpha comes from the fog and the CG sphere), the light layers on.
TEST(Builtins, HoldoutHasHeldOutShapesInAndAroundTheFog) {
  const SceneDesc scene = parse_builtin(*find_builtin("holdout"));
  int holdouts = 0, visible = 0;
  for (const ShapeDesc& s : scene.shapes) (s.holdout ? holdouts : visible) += 1;
  EXPECT_EQ(holdouts, 3);
  EXPECT_EQ(visible, 1);
  ASSERT_EQ(scene.volumes.size(), 1u);
  const Bounds3 fog = volume_bounds(scene.volumes[0].shape);
  // The held-out sphere straddles the fog's back face (behind it and inside it).
  const auto& back = std::get<SphereShape>(scene.shapes[2].geometry);
  EXPECT_TRUE(scene.shapes[2].holdout);
  EXPECT_LT(back.center.z - back.radius, fog.lo.z);
  EXPECT_GT(back.center.z + back.radius, fog.lo.z);
  // The knot is placed at the fog's front face, the side the camera is on.
  EXPECT_TRUE(scene.shapes[1].holdout);
  EXPECT_FLOAT_EQ(scene.shapes[1].transform.point({0, 0, 0}).z, fog.hi.z);
  EXPECT_GT(scene.camera.position.z, fog.hi.z);
  bool invisible_sky = false;
  for (const Light& l : scene.lights)
    if (const auto* env = std::get_if<EnvironmentLight>(&l)) invisible_sky = !env->visible;
  EXPECT_TRUE(invisible_sky);
  const AovSet aovs = scene.render.aovs;
  EXPECT_TRUE(aovs.has(Aov::kAlpha));
  for (int k = 0; k < kLightKindCount; ++k) EXPECT_TRUE(aovs.has(light_aov(LightKind(k)))) << k;
}

TEST(Builtins, DefaultRoomIsClosedAroundTheCamera) {
  const SceneDesc scene = parse_builtin(*find_builtin("default"));
  // Six walls: the camera is inside the box they bound.
  int walls = 0;
  for (const ShapeDesc& s : scene.shapes) walls += std::holds_alternative<RectangleShape>(s.geometry);
  EXPECT_EQ(walls, 6);
  const Vec3 p = scene.camera.position;
  EXPECT_TRUE(p.x > -2 && p.x < 2 && p.y > 0 && p.y < 4 && p.z > -2 && p.z < 5);
  ASSERT_EQ(scene.lights.size(), 2u);
  EXPECT_TRUE(std::holds_alternative<QuadLight>(scene.lights[0]));
  EXPECT_TRUE(std::holds_alternative<PointLight>(scene.lights[1]));
  // Thin fog fills the room.
  ASSERT_EQ(scene.volumes.size(), 1u);
  EXPECT_TRUE(std::holds_alternative<BoxVolumeShape>(scene.volumes[0].shape));
  EXPECT_EQ(scene.render.spp, 64);
  EXPECT_EQ(scene.render.path.limits.max_bounces, 8);
}

TEST(Builtins, LightsShowcaseHasEveryFileLightType) {
  const SceneDesc scene = parse_builtin(*find_builtin("lights-showcase"));
  std::set<size_t> kinds;
  for (const Light& l : scene.lights) kinds.insert(l.index());
  EXPECT_EQ(kinds.size(), 6u);  // every type a scene file can name (triangle lights come from meshes)
  for (const Light& l : scene.lights)
    if (const auto* sun = std::get_if<DirectionalLight>(&l)) {
      EXPECT_LT(sun->cos_angular_radius, 1.0f);
    }
}

}  // namespace
}  // namespace caligo

namespace caligo {
namespace {

TEST(Builtins, VolumeScenesHaveTheirMedia) {
  const SceneDesc lamp = parse_builtin(*find_builtin("lamp-in-fog"));
  ASSERT_EQ(lamp.volumes.size(), 1u);
  ASSERT_EQ(lamp.lights.size(), 1u);
  const auto& fog = std::get<SphereVolumeShape>(lamp.volumes[0].shape);
  // The lamp is inside its fog sphere.
  EXPECT_LT(length(fog.sphere.object_to_world.inverse_point(std::get<PointLight>(lamp.lights[0]).position)),
            1.0f);
  const SceneDesc shafts = parse_builtin(*find_builtin("spot-shafts"));
  EXPECT_TRUE(std::holds_alternative<SpotLight>(shafts.lights[0]));
  EXPECT_EQ(parse_builtin(*find_builtin("overlap")).volumes.size(), 2u);
}

}  // namespace
}  // namespace caligo

namespace caligo {
namespace {

// The Wyman & Ramsey family: one point light, homogeneous fog, a ground and a generated
// closed occluder of the size in the name; each "-spot" variant is the same scene lit by a
// textured spotlight at the point light's position, aimed at the occluder.
TEST(Builtins, WymanScenesHaveAPointLightFogAndASizedOccluder) {
  for (const auto& [name, triangles] : {std::pair{"wyman-20k", 20000u}, std::pair{"wyman-70k", 70000u},
                                        std::pair{"wyman-330k", 300000u}, std::pair{"wyman-750k", 750000u}}) {
    SCOPED_TRACE(name);
    const SceneDesc scene = parse_builtin(*find_builtin(name));
    ASSERT_EQ(scene.lights.size(), 1u);
    EXPECT_TRUE(std::holds_alternative<PointLight>(scene.lights[0]));
    ASSERT_EQ(scene.volumes.size(), 1u);
    EXPECT_TRUE(is_homogeneous(scene.volumes[0].shader));
    ASSERT_EQ(scene.shapes.size(), 2u);
    EXPECT_EQ(std::get<GeneratedMeshShape>(scene.shapes[1].geometry).triangles, triangles);

    const std::string spot_name = std::string(name) + "-spot";
    SCOPED_TRACE(spot_name);
    const BuiltinScene* spot_builtin = find_builtin(spot_name);
    ASSERT_NE(spot_builtin, nullptr);
    EXPECT_NE(spot_builtin->description.find("textured spotlight"), std::string::npos);
    const SceneDesc spot_scene = parse_builtin(*spot_builtin);
    ASSERT_EQ(spot_scene.lights.size(), 1u);
    const auto* spot = std::get_if<SpotLight>(&spot_scene.lights[0]);
    ASSERT_NE(spot, nullptr);
    ASSERT_TRUE(spot->gobo.image);
    EXPECT_EQ(spot->gobo.image->width(), 256);
    EXPECT_EQ(spot->position, std::get<PointLight>(scene.lights[0]).position);
    const Vec3 to_occluder = normalize(Vec3(0, 1.6f, 0) - spot->position);
    EXPECT_NEAR(dot(spot->direction, to_occluder), 1.0f, 1e-6f);
    EXPECT_EQ(spot_scene.options(0).shadow_map_size, scene.options(0).shadow_map_size);
    // Everything but the light is the point-light scene's.
    ASSERT_EQ(spot_scene.volumes.size(), 1u);
    EXPECT_TRUE(is_homogeneous(spot_scene.volumes[0].shader));
    ASSERT_EQ(spot_scene.shapes.size(), 2u);
    const auto& occluder = std::get<GeneratedMeshShape>(spot_scene.shapes[1].geometry);
    EXPECT_EQ(occluder.triangles, triangles);
    EXPECT_EQ(occluder.kind, std::get<GeneratedMeshShape>(scene.shapes[1].geometry).kind);
    EXPECT_EQ(spot_scene.camera.position, scene.camera.position);
  }
}

}  // namespace
}  // namespace caligo
