#include "scene/scene_parser.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/math.h"
#include "settings/aov.h"

namespace caligo {
namespace {

namespace fs = std::filesystem;
using OJson = nlohmann::ordered_json;

// One of every object the format has, with values whose conversions are easy to check.
constexpr const char* kEverything = R"json({
  "camera": {"position": [1, 2, 3], "look_at": [1, 2, 0], "up": [0, 2, 0], "fov": 50,
             "resolution": [320, 200]},
  "render": {"spp": 128, "max_depth": 12, "seed": 18446744073709551615},
  "materials": {
    "white": {"type": "diffuse", "reflectance": 0.5},
    "red": {"type": "diffuse", "reflectance": [0.9, 0.1, 0.1], "emission": [1, 2, 3], "two_sided": true},
    "glass": {"type": "dielectric", "ior": 1.33},
    "lamp": {"type": "emissive", "radiance": 10, "color": [1, 0.5, 0.25], "two_sided": true},
    "portal": {"type": "null"}
  },
  "shapes": [
    {"type": "sphere", "center": [0, 1, 0], "radius": 0.5, "material": "glass",
     "transform": [{"scale": 2}, {"translate": [1, 0, 0]}]},
    {"type": "box", "min": [-1, -1, -1], "max": [1, 2, 3], "material": "white",
     "transform": [{"rotate": {"angle": 90, "axis": [0, 0, 1]}}, {"translate": [0, 0, 5]}]},
    {"type": "rectangle", "corner": [0, 0, 0], "edge1": [1, 0, 0], "edge2": [0, 1, 0], "material": "lamp"},
    {"type": "mesh", "file": "meshes/bunny.obj", "material": "portal",
     "transform": [{"matrix": [1, 0, 0, 5, 0, 1, 0, 6, 0, 0, 1, 7, 0, 0, 0, 1]}, {"scale": [1, 2, -1]}]}
  ],
  "lights": [
    {"type": "point", "position": [0, 3, 0], "color": [1, 0.5, 1], "power": 100},
    {"type": "point", "position": [0, 3, 1], "intensity": [1, 2, 3]},
    {"type": "spot", "position": [0, 4, 0], "look_at": [0, 0, 0], "inner_angle": 30, "outer_angle": 60,
     "power": 50},
    {"type": "spot", "position": [0, 4, 0], "direction": [0, 0, -2], "inner_angle": 10, "outer_angle": 10,
     "intensity": 7},
    {"type": "sphere", "center": [1, 1, 1], "radius": 0.5, "power": 10},
    {"type": "quad", "corner": [0, 0, 0], "edge1": [2, 0, 0], "edge2": [0, 0, 3], "color": 2,
     "power": 18.84955592},
    {"type": "quad", "corner": [0, 0, 0], "edge1": [2, 0, 0], "edge2": [0, 0, 3], "two_sided": true,
     "radiance": [1, 2, 3]},
    {"type": "quad", "corner": [0, 0, 0], "edge1": [2, 0, 0], "edge2": [0, 0, 3], "two_sided": true,
     "power": 12},
    {"type": "directional", "direction": [0, -2, 0], "irradiance": 3, "angular_radius": 0.5},
    {"type": "environment", "color": [0.5, 0.5, 1], "radiance": 2}
  ]
})json";

void expect_rgb_near(RGB actual, RGB expected, float tolerance = 1e-5f) {
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(actual[i], expected[i], tolerance * std::max(1.0f, std::abs(expected[i])));
}
void expect_vec_near(Vec3 actual, Vec3 expected, float tolerance = 1e-5f) {
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(actual[i], expected[i], tolerance);
}

class EverythingTest : public ::testing::Test {
 protected:
  SceneDesc scene = parse_scene_text(kEverything, "all.json", "/scenes");
};

TEST_F(EverythingTest, CameraAndRenderSettings) {
  EXPECT_EQ(scene.file, "all.json");
  EXPECT_EQ(scene.camera.position, Vec3(1, 2, 3));
  EXPECT_EQ(scene.camera.look_at, Vec3(1, 2, 0));
  expect_vec_near(scene.camera.up, {0, 1, 0});
  EXPECT_FLOAT_EQ(scene.camera.fov_degrees, 50.0f);
  EXPECT_EQ(scene.camera.resolution, (Vec2i{320, 200}));
  EXPECT_EQ(scene.render.spp, 128);
  EXPECT_EQ(scene.render.path.limits.max_bounces, 12);
  EXPECT_EQ(scene.render.seed, 18446744073709551615ull);
}

TEST_F(EverythingTest, MaterialsKeepFileOrder) {
  ASSERT_EQ(scene.materials.size(), 5u);
  const char* names[] = {"white", "red", "glass", "lamp", "portal"};
  for (int i = 0; i < 5; ++i) EXPECT_EQ(scene.materials[i].name, names[i]);
  expect_rgb_near(std::get<DiffuseBsdf>(scene.materials[0].bsdf).reflectance, RGB(0.5f));
  EXPECT_TRUE(scene.materials[0].emission.is_black());
  expect_rgb_near(std::get<DiffuseBsdf>(scene.materials[1].bsdf).reflectance, {0.9f, 0.1f, 0.1f});
  expect_rgb_near(scene.materials[1].emission, {1, 2, 3});
  EXPECT_TRUE(scene.materials[1].two_sided_emission);
  EXPECT_FLOAT_EQ(std::get<DielectricBsdf>(scene.materials[2].bsdf).ior, 1.33f);
  EXPECT_TRUE(std::holds_alternative<BlackBsdf>(scene.materials[3].bsdf));
  expect_rgb_near(scene.materials[3].emission, {10, 5, 2.5f});
  EXPECT_TRUE(scene.materials[3].two_sided_emission);
  EXPECT_TRUE(std::holds_alternative<NullBsdf>(scene.materials[4].bsdf));
}

TEST_F(EverythingTest, ShapesAndTransformOrder) {
  ASSERT_EQ(scene.shapes.size(), 4u);
  const ShapeDesc& sphere = scene.shapes[0];
  EXPECT_EQ(std::get<SphereShape>(sphere.geometry).center, Vec3(0, 1, 0));
  EXPECT_FLOAT_EQ(std::get<SphereShape>(sphere.geometry).radius, 0.5f);
  EXPECT_EQ(sphere.material, 2);
  EXPECT_EQ(sphere.where.file, "all.json");
  EXPECT_EQ(sphere.where.json_path, "/shapes/0");
  // Scale first, then translate: (1,0,0) -> (2,0,0) -> (3,0,0). The other order would give (4,0,0).
  expect_vec_near(sphere.transform.point({1, 0, 0}), {3, 0, 0});

  const ShapeDesc& box = scene.shapes[1];
  EXPECT_EQ(std::get<BoxShape>(box.geometry).min, Vec3(-1, -1, -1));
  EXPECT_EQ(std::get<BoxShape>(box.geometry).max, Vec3(1, 2, 3));
  EXPECT_EQ(box.material, 0);
  // Rotate 90 degrees about +Z (counter-clockwise), then translate: (1,0,0) -> (0,1,0) -> (0,1,5).
  expect_vec_near(box.transform.point({1, 0, 0}), {0, 1, 5});

  const auto& rect = std::get<RectangleShape>(scene.shapes[2].geometry);
  EXPECT_EQ(rect.edge2, Vec3(0, 1, 0));
  EXPECT_EQ(scene.shapes[2].material, 3);
  EXPECT_TRUE(scene.shapes[2].transform.is_identity());

  const ShapeDesc& mesh = scene.shapes[3];
  EXPECT_EQ(std::get<MeshFileShape>(mesh.geometry).path, "/scenes/meshes/bunny.obj");
  EXPECT_EQ(mesh.material, 4);
  // Matrix (translate by (5,6,7)) first, then scale by (1,2,-1).
  expect_vec_near(mesh.transform.point({0, 0, 0}), {5, 12, -7});
  EXPECT_TRUE(mesh.transform.swaps_handedness());
}

TEST_F(EverythingTest, PointLightsConvertPower) {
  ASSERT_EQ(scene.lights.size(), 10u);
  const auto& from_power = std::get<PointLight>(scene.lights[0]);
  EXPECT_EQ(from_power.position, Vec3(0, 3, 0));
  const float i = 100.0f / (4.0f * kPi);  // P = 4 pi I
  expect_rgb_near(from_power.intensity, {i, 0.5f * i, i});
  expect_rgb_near(std::get<PointLight>(scene.lights[1]).intensity, {1, 2, 3});
}

TEST_F(EverythingTest, SpotLightsConvertAnglesAndPower) {
  const auto& spot = std::get<SpotLight>(scene.lights[2]);
  expect_vec_near(spot.direction, {0, -1, 0});
  EXPECT_NEAR(spot.cos_inner, std::sqrt(3.0) / 2.0, 1e-6);
  EXPECT_NEAR(spot.cos_outer, 0.5, 1e-6);
  const double i = 50.0 / (2.0 * M_PI * (1.0 - (std::sqrt(3.0) / 2.0 + 0.5) / 2.0));
  expect_rgb_near(spot.intensity, RGB(float(i)));

  const auto& aimed = std::get<SpotLight>(scene.lights[3]);
  expect_vec_near(aimed.direction, {0, 0, -1});
  EXPECT_FLOAT_EQ(aimed.cos_inner, aimed.cos_outer);
  expect_rgb_near(aimed.intensity, RGB(7));
}

TEST_F(EverythingTest, AreaLightsConvertPower) {
  const auto& sphere = std::get<SphereLight>(scene.lights[4]);
  EXPECT_EQ(sphere.center, Vec3(1, 1, 1));
  EXPECT_FLOAT_EQ(sphere.radius, 0.5f);
  // P = pi L (4 pi r^2)
  expect_rgb_near(sphere.radiance, RGB(float(10.0 / (4.0 * M_PI * M_PI * 0.25))));

  // Area 6 m^2, P = 6 pi W one-sided -> L = 1, times color 2.
  const auto& quad = std::get<QuadLight>(scene.lights[5]);
  EXPECT_FALSE(quad.two_sided);
  EXPECT_EQ(quad.edge2, Vec3(0, 0, 3));
  expect_rgb_near(quad.radiance, RGB(2));
  expect_rgb_near(std::get<QuadLight>(scene.lights[6]).radiance, {1, 2, 3});
  // Two-sided: P = 2 pi L A.
  const auto& two_sided = std::get<QuadLight>(scene.lights[7]);
  EXPECT_TRUE(two_sided.two_sided);
  expect_rgb_near(two_sided.radiance, RGB(float(12.0 / (2.0 * M_PI * 6.0))));
}

TEST_F(EverythingTest, DistantLights) {
  const auto& sun = std::get<DirectionalLight>(scene.lights[8]);
  expect_vec_near(sun.direction, {0, -1, 0});
  expect_rgb_near(sun.irradiance, RGB(3));
  EXPECT_NEAR(sun.cos_angular_radius, std::cos(0.5 * M_PI / 180.0), 1e-7);
  expect_rgb_near(std::get<EnvironmentLight>(scene.lights[9]).radiance, {1, 1, 2});
}

// "max_bounces" is the documented name; "max_depth" (EverythingTest) its alias.
TEST(SceneParser, MaxBounces) {
  const SceneDesc scene = parse_scene_text(
      R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]}, "render": {"max_bounces": 3}})", "b.json", "");
  EXPECT_EQ(scene.render.path.limits.max_bounces, 3);
  EXPECT_EQ(scene.render.path.limits.max_volume_bounces, 1024);  // the default
}

// "holdout" marks a shape as a matte; it is off unless given.
TEST(SceneParser, HoldoutShapes) {
  const SceneDesc scene = parse_scene_text(R"json({
    "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
    "materials": {"w": {"type": "diffuse", "reflectance": 0.5}},
    "shapes": [
      {"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "w", "holdout": true},
      {"type": "box", "min": [-1, -1, -1], "max": [1, 1, 1], "material": "w", "holdout": false},
      {"type": "rectangle", "corner": [0, 0, 0], "edge1": [1, 0, 0], "edge2": [0, 0, 1], "material": "w"},
      {"type": "mesh", "generate": {"kind": "sphere", "triangles": 80}, "material": "w", "holdout": true}
    ]})json",
                                           "h.json", "");
  ASSERT_EQ(scene.shapes.size(), 4u);
  EXPECT_TRUE(scene.shapes[0].holdout);
  EXPECT_FALSE(scene.shapes[1].holdout);
  EXPECT_FALSE(scene.shapes[2].holdout);
  EXPECT_TRUE(scene.shapes[3].holdout);
}

// "proxy": a closed shape for the hybrid's shadow volumes, with geometry keys only.
TEST(SceneParser, ShadowProxies) {
  const auto scene_with = [](const std::string& proxy) {
    return R"json({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
      "materials": {"w": {"type": "diffuse", "reflectance": 0.5}},
      "shapes": [{"type": "mesh", "generate": {"kind": "torus_knot", "triangles": 2000}, "material": "w",
                  "proxy": )json" + proxy + "}]}";
  };
  const SceneDesc scene = parse_scene_text(scene_with(R"({"type": "box", "min": [-1, -1, -1], "max": [1, 1, 1]})"),
                                           "p.json", "");
  ASSERT_TRUE(scene.shapes[0].proxy);
  EXPECT_TRUE(std::holds_alternative<BoxShape>(*scene.shapes[0].proxy));
  try {
    parse_scene_text(scene_with(R"({"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "w"})"), "p.json",
                     "");
    ADD_FAILURE() << "a proxy with a material";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().json_path, "/shapes/0/proxy/material");
  }
  EXPECT_THROW(parse_scene_text(scene_with(R"({"type": "rectangle", "corner": [0, 0, 0], "edge1": [1, 0, 0],
                                              "edge2": [0, 1, 0]})"),
                                "p.json", ""),
               InputError);
}

// "render.aovs": exactly the listed outputs (the beauty always), with --aov's names and shortcuts.
TEST(SceneParser, RenderAovs) {
  const auto aovs_of = [](const std::string& render) {
    return parse_scene_text(R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]}, "render": )" + render + "}",
                            "a.json", "")
        .render.aovs;
  };
  EXPECT_EQ(aovs_of("{}"), AovSet::defaults());
  EXPECT_EQ(aovs_of(R"({"aovs": []})"), AovSet{});
  EXPECT_EQ(aovs_of(R"({"aovs": ["alpha", "volume.direct", "beauty"]})"),
            AovSet{}.with(Aov::kAlpha).with(Aov::kVolumeDirect));
  EXPECT_EQ(aovs_of(R"({"aovs": ["all"]})"), AovSet::all());
  AovSet lights_and_default = AovSet::defaults();
  for (int k = 0; k < kLightKindCount; ++k) lights_and_default = lights_and_default.with(light_aov(LightKind(k)));
  EXPECT_EQ(aovs_of(R"({"aovs": ["lights", "default"]})"), lights_and_default);
  EXPECT_EQ(aovs_of(R"({"aovs": ["default"]})"), AovSet::defaults());
}

TEST(SceneParser, DefaultsForOptionalParts) {
  const SceneDesc scene =
      parse_scene_text(R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]}})", "min.json", "");
  EXPECT_EQ(scene.camera.up, Vec3(0, 1, 0));
  EXPECT_FLOAT_EQ(scene.camera.fov_degrees, 40.0f);
  EXPECT_EQ(scene.camera.resolution, (Vec2i{640, 480}));
  EXPECT_EQ(scene.render.spp, 16);
  EXPECT_EQ(scene.render.path.limits.max_bounces, 8);
  EXPECT_TRUE(scene.materials.empty());
  EXPECT_TRUE(scene.shapes.empty());
  EXPECT_TRUE(scene.lights.empty());  // allowed: the image is black
}

// A light given by "power" must report that power back through power(Light).
TEST(SceneParser, PowerRoundTripsThroughEveryLightType) {
  const SceneDesc scene = parse_scene_text(R"json({
    "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
    "lights": [
      {"type": "point", "position": [0, 0, 0], "power": 100},
      {"type": "spot", "position": [0, 0, 0], "direction": [0, 1, 0], "inner_angle": 5, "outer_angle": 150,
       "power": 100},
      {"type": "sphere", "center": [0, 0, 0], "radius": 0.3, "power": 100},
      {"type": "sphere", "center": [0, 0, 0], "radius": 0.3, "two_sided": true, "power": 100},
      {"type": "quad", "corner": [0, 0, 0], "edge1": [0.5, 0, 0], "edge2": [0.3, 0.4, 0], "power": 100},
      {"type": "quad", "corner": [0, 0, 0], "edge1": [0.5, 0, 0], "edge2": [0.3, 0.4, 0], "two_sided": true,
       "power": 100},
      {"type": "disk", "center": [0, 1, 0], "normal": [0, -2, 0], "radius": 0.4, "two_sided": true, "power": 100}
    ]})json",
                                           "power.json", "");
  ASSERT_EQ(scene.lights.size(), 7u);
  const auto& disk = std::get<DiskLight>(scene.lights[6]);
  EXPECT_FLOAT_EQ(disk.normal.y, -1.0f);  // normalised
  EXPECT_FLOAT_EQ(disk.radius, 0.4f);
  for (const Light& light : scene.lights) EXPECT_NEAR(power(light), 100.0f, 1e-3f) << light.index();
  EXPECT_TRUE(std::get<SphereLight>(scene.lights[3]).two_sided);
}

TEST(SceneParser, ZeroPowerLightIsAllowed) {
  const SceneDesc scene = parse_scene_text(
      R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
          "lights": [{"type": "point", "position": [0, 0, 0], "power": 0}]})",
      "dark.json", "");
  EXPECT_TRUE(std::get<PointLight>(scene.lights[0]).intensity.is_black());
}

// ---- bad input: each case names the JSON pointer and a key part of the message ----

// A small valid scene the cases below break one piece at a time.
OJson base_scene() {
  return OJson::parse(R"json({
    "camera": {"position": [0, 1, 5], "look_at": [0, 1, 0]},
    "materials": {"white": {"type": "diffuse", "reflectance": 0.5}, "glass": {"type": "dielectric"}},
    "shapes": [
      {"type": "sphere", "center": [0, 1, 0], "radius": 1, "material": "white"},
      {"type": "box", "min": [-1, 0, -1], "max": [1, 1, 1], "material": "glass"},
      {"type": "rectangle", "corner": [0, 0, 0], "edge1": [1, 0, 0], "edge2": [0, 0, 1], "material": "white"}
    ],
    "lights": [
      {"type": "point", "position": [0, 3, 0], "intensity": 1},
      {"type": "spot", "position": [0, 3, 0], "look_at": [0, 0, 0], "inner_angle": 20, "outer_angle": 30,
       "power": 10}
    ]
  })json");
}

TEST(SceneParser, BaseSceneIsValid) { EXPECT_NO_THROW(parse_scene_text(base_scene().dump(), "t.json", "")); }

struct BadCase {
  const char* name;
  std::function<void(OJson&)> edit;
  const char* pointer;
  const char* message_part;
};

std::ostream& operator<<(std::ostream& os, const BadCase& c) { return os << c.name; }

const BadCase kBadCases[] = {
    {"UnknownKey",
     [](OJson& s) {
       s["lights"][0]["colour"] = {1, 0, 0};
     },
     "/lights/0/colour",
     R"(unknown key "colour" in a point light (did you mean "color"?); allowed keys: type, position, color, )"
     "intensity, power"},
    {"UnknownTopLevelKey", [](OJson& s) { s["version"] = 1; }, "/version",
     R"(unknown key "version" in a scene)"},
    {"UnknownCameraKey", [](OJson& s) { s["camera"]["aperture"] = 1; }, "/camera/aperture",
     "allowed keys: position"},
    {"WrongType", [](OJson& s) { s["lights"][0]["intensity"] = "bright"; }, "/lights/0/intensity",
     R"(expected a number or an array of 3 numbers, got "bright")"},
    {"WrongVectorLength",
     [](OJson& s) {
       s["shapes"][0]["center"] = {0, 1};
     },
     "/shapes/0/center", "expected an array of 3 numbers, got [0,1]"},
    {"WrongTypeInVector",
     [](OJson& s) {
       s["camera"]["position"] = {0, "1", 5};
     },
     "/camera/position/1", R"(expected a number, got "1")"},
    {"ShapesNotArray", [](OJson& s) { s["shapes"] = OJson::object(); }, "/shapes",
     "expected an array of shapes, got {}"},
    {"MissingRequiredKey", [](OJson& s) { s["shapes"][0].erase("radius"); }, "/shapes/0",
     R"(missing required key "radius" in a sphere shape)"},
    {"MissingCamera", [](OJson& s) { s.erase("camera"); }, "", R"(missing required key "camera")"},
    {"MissingMaterialKey", [](OJson& s) { s["shapes"][1].erase("material"); }, "/shapes/1",
     R"(missing required key "material" in a box shape)"},
    {"TooLargeForFloat", [](OJson& s) { s["shapes"][0]["radius"] = 1e39; }, "/shapes/0/radius",
     "expected a finite number, got 1e+39 (too large for a 32-bit float)"},
    {"NegativeRadius", [](OJson& s) { s["shapes"][0]["radius"] = -1; }, "/shapes/0/radius",
     "expected a number in [1e-06, 10000000], got -1"},
    {"ZeroRadius", [](OJson& s) { s["shapes"][0]["radius"] = 0; }, "/shapes/0/radius",
     "expected a number in [1e-06, 10000000], got 0"},
    {"FlatBox",
     [](OJson& s) {
       s["shapes"][1]["max"] = {1, 0, 1};
     },
     "/shapes/1/max", "expected max > min in every component (min is [-1, 0, -1]), got [1,0,1]"},
    {"ZeroLengthEdge",
     [](OJson& s) {
       s["shapes"][2]["edge1"] = {0, 0, 0};
     },
     "/shapes/2/edge1", "expected a non-zero edge"},
    {"ParallelEdges",
     [](OJson& s) {
       s["shapes"][2]["edge2"] = {-2, 0, 0};
     },
     "/shapes/2/edge2", "not parallel to edge1"},
    {"ZeroResolution",
     [](OJson& s) {
       s["camera"]["resolution"] = {0, 480};
     },
     "/camera/resolution/0", "expected an integer in [1, 16384], got 0"},
    {"HugeResolution",
     [](OJson& s) {
       s["camera"]["resolution"] = {640, 20000};
     },
     "/camera/resolution/1", "expected an integer in [1, 16384], got 20000"},
    {"ResolutionNotPair", [](OJson& s) { s["camera"]["resolution"] = {640}; }, "/camera/resolution",
     "expected an array of 2 integers [width, height], got [640]"},
    {"FractionalResolution",
     [](OJson& s) {
       s["camera"]["resolution"] = {640.5, 480};
     },
     "/camera/resolution/0", "expected an integer in [1, 16384], got 640.5"},
    {"ZeroSpp", [](OJson& s) { s["render"]["spp"] = 0; }, "/render/spp",
     "expected an integer in [1, 1000000], got 0"},
    {"HugeSpp", [](OJson& s) { s["render"]["spp"] = 2000000; }, "/render/spp",
     "in [1, 1000000], got 2000000"},
    {"NegativeMaxDepth", [](OJson& s) { s["render"]["max_depth"] = -1; }, "/render/max_depth",
     "expected an integer in [0, 10000], got -1"},
    {"HugeMaxBounces", [](OJson& s) { s["render"]["max_bounces"] = 10001; }, "/render/max_bounces",
     "expected an integer in [0, 10000], got 10001"},
    {"MaxDepthAliasWithMaxBounces",
     [](OJson& s) {
       s["render"]["max_bounces"] = 4;
       s["render"]["max_depth"] = 4;
     },
     "/render/max_depth", R"("max_depth" is an alias of "max_bounces")"},
    {"NegativeSeed", [](OJson& s) { s["render"]["seed"] = -3; }, "/render/seed",
     "expected an integer >= 0, got -3"},
    {"FovTooWide", [](OJson& s) { s["camera"]["fov"] = 180; }, "/camera/fov",
     "expected a number in (0, 180), got 180"},
    {"UnknownMaterial", [](OJson& s) { s["shapes"][0]["material"] = "whte"; }, "/shapes/0/material",
     R"(unknown material "whte" (did you mean "white"?); defined materials: white, glass)"},
    {"DuplicateMaterial", [](OJson&) {}, "/materials/white",
     R"(duplicate key "white")"},  // text edited below
    {"UnknownMaterialType", [](OJson& s) { s["materials"]["white"]["type"] = "metal"; },
     "/materials/white/type",
     R"(unknown type "metal" for a material; valid values: diffuse, dielectric, emissive, null)"},
    {"UnknownShapeType", [](OJson& s) { s["shapes"][0]["type"] = "cone"; }, "/shapes/0/type",
     R"(unknown type "cone" for a shape; valid values: sphere, box, rectangle, mesh)"},
    {"UnknownLightType", [](OJson& s) { s["lights"][0]["type"] = "laser"; }, "/lights/0/type",
     R"(unknown type "laser" for a light; valid values: point, spot, box, sphere, quad, )"},
    {"ReflectanceAboveOne",
     [](OJson& s) {
       s["materials"]["white"]["reflectance"] = {0.5, 1.5, 0.5};
     },
     "/materials/white/reflectance/1", "expected a number in [0, 1], got 1.5"},
    {"NegativeEmission", [](OJson& s) { s["materials"]["white"]["emission"] = -1; },
     "/materials/white/emission", "expected a number >= 0, got -1"},
    {"NegativeColor",
     [](OJson& s) {
       s["lights"][0]["color"] = {-1, 1, 1};
     },
     "/lights/0/color/0", "expected a number >= 0, got -1"},
    {"IorBelowOne", [](OJson& s) { s["materials"]["glass"]["ior"] = 0.9; }, "/materials/glass/ior",
     "expected a number in [1, 10], got 0.9"},
    {"IorAbsurd", [](OJson& s) { s["materials"]["glass"]["ior"] = 150; }, "/materials/glass/ior",
     "in [1, 10]"},
    {"KeyOfOtherMaterialType", [](OJson& s) { s["materials"]["glass"]["reflectance"] = 0.5; },
     "/materials/glass/reflectance",
     R"(unknown key "reflectance" in a dielectric material; allowed keys: type, ior)"},
    {"InnerAboveOuter", [](OJson& s) { s["lights"][1]["inner_angle"] = 40; }, "/lights/1/inner_angle",
     "expected inner_angle <= outer_angle (30), got 40"},
    {"OuterAngleOutOfRange", [](OJson& s) { s["lights"][1]["outer_angle"] = 180; }, "/lights/1/outer_angle",
     "expected a number in (0, 179], got 180"},
    {"SpotAimedAtItself",
     [](OJson& s) {
       s["lights"][1]["look_at"] = {0, 3, 0};
     },
     "/lights/1/look_at", "expected a point different from position [0, 3, 0]"},
    {"SpotWithLookAtAndDirection",
     [](OJson& s) {
       s["lights"][1]["direction"] = {0, -1, 0};
     },
     "/lights/1", R"(expected exactly one of "look_at" or "direction" in a spot light, got both)"},
    {"IntensityAndPower", [](OJson& s) { s["lights"][0]["power"] = 10; }, "/lights/0",
     R"(expected exactly one of "intensity" or "power" in a point light, got both)"},
    {"NeitherIntensityNorPower", [](OJson& s) { s["lights"][0].erase("intensity"); }, "/lights/0",
     R"(expected exactly one of "intensity" or "power" in a point light, got neither)"},
    {"SunTooWide",
     [](OJson& s) {
       s["lights"][0] = {
           {"type", "directional"}, {"direction", {0, -1, 0}}, {"irradiance", 1}, {"angular_radius", 50}};
     },
     "/lights/0/angular_radius", "expected a number in [0, 45], got 50"},
    {"ZeroDirection",
     [](OJson& s) {
       s["lights"][0] = {{"type", "directional"}, {"direction", {0, 0, 0}}, {"irradiance", 1}};
     },
     "/lights/0/direction", "expected a non-zero direction, got [0,0,0]"},
    {"LookAtIsPosition",
     [](OJson& s) {
       s["camera"]["look_at"] = {0, 1, 5};
     },
     "/camera/look_at", "expected a point different from position [0, 1, 5], got the same point"},
    {"UpParallelToView",
     [](OJson& s) {
       s["camera"]["up"] = {0, 0, 2};
     },
     "/camera/up", "expected an up vector not parallel to the view direction [0, 0, -1], got [0,0,2]"},
    {"VerticalViewWithDefaultUp",
     [](OJson& s) {
       s["camera"]["look_at"] = {0, -3, 5};
     },
     "/camera", "parallel to the default up [0, 1, 0]"},
    {"SingularMatrix",
     [](OJson& s) {
       s["shapes"][0]["transform"] = {{{"matrix", {1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}}}};
     },
     "/shapes/0/transform/0/matrix", "expected an invertible matrix, got a singular one"},
    {"ProjectiveMatrix",
     [](OJson& s) {
       s["shapes"][0]["transform"] = {{{"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 1, 1}}}};
     },
     "/shapes/0/transform/0/matrix", "expected the last row to be [0, 0, 0, 1]"},
    {"NearlyFlatTransform",
     [](OJson& s) {
       // Each factor is allowed; their product is not.
       s["shapes"][0]["transform"] = {
           {{"scale", {1, 1e-5, 1}}}, {{"scale", {1, 1e-5, 1}}}, {{"scale", {1, 1e-5, 1}}}};
     },
     "/shapes/0/transform", "expected an invertible transform"},
    {"TinyScale",
     [](OJson& s) {
       s["shapes"][0]["transform"] = {{{"scale", {1, 1e-20, 1}}}};
     },
     "/shapes/0/transform/0/scale", "expected scale factors of magnitude in [1e-06, 1e+06]"},
    {"ZeroScale",
     [](OJson& s) {
       s["shapes"][0]["transform"] = {{{"scale", {1, 0, 1}}}};
     },
     "/shapes/0/transform/0/scale", "expected non-zero scale factors"},
    {"TwoOpsInOne",
     [](OJson& s) {
       s["shapes"][0]["transform"] = {{{"scale", 2}, {"translate", {1, 0, 0}}}};
     },
     "/shapes/0/transform/0", "expected exactly one of translate, rotate, scale, matrix"},
    {"UnknownTransformOp",
     [](OJson& s) {
       s["shapes"][0]["transform"] = {{{"shear", 2}}};
     },
     "/shapes/0/transform/0/shear", R"(unknown key "shear" in a transform operation)"},
    {"RotationWithoutAxis",
     [](OJson& s) {
       s["shapes"][0]["transform"] = {{{"rotate", {{"angle", 30}}}}};
     },
     "/shapes/0/transform/0/rotate", R"(missing required key "axis" in a rotation)"},
    {"MeshExtension",
     [](OJson& s) {
       s["shapes"][0] = {{"type", "mesh"}, {"file", "bunny.3ds"}, {"material", "white"}};
     },
     "/shapes/0/file", R"(expected a mesh file ending in .obj, .gltf, .glb, .ply, .dae, .stl or .off, got "bunny.3ds")"},
    {"SceneNotObject", [](OJson& s) { s = OJson::array(); }, "", "expected a scene (a JSON object), got []"},
    {"HoldoutNotBoolean", [](OJson& s) { s["shapes"][2]["holdout"] = 1; }, "/shapes/2/holdout",
     "expected true or false, got 1"},
    {"HoldoutAsString", [](OJson& s) { s["shapes"][0]["holdout"] = "yes"; }, "/shapes/0/holdout",
     R"(expected true or false, got "yes")"},
    {"AovsNotArray", [](OJson& s) { s["render"] = {{"aovs", "alpha"}}; }, "/render/aovs",
     R"(expected an array of output names, got "alpha")"},
    {"UnknownAov", [](OJson& s) { s["render"] = {{"aovs", {"alpha", "volume_drect"}}}; }, "/render/aovs/1",
     R"(unknown output "volume_drect" in render.aovs)"},
    {"AovNotString", [](OJson& s) { s["render"] = {{"aovs", {3}}}; }, "/render/aovs/0", "expected a string"},
};

class BadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadInput, NamesPointerAndProblem) {
  const BadCase& c = GetParam();
  OJson scene = base_scene();
  c.edit(scene);
  std::string text = scene.dump(2);
  if (std::string_view(c.name) == "DuplicateMaterial") {
    const std::string glass = R"("glass": {)";
    text.replace(text.find(glass), glass.size(), R"("white": {)");
  }
  try {
    parse_scene_text(text, "bad.json", "");
    FAIL() << "no error for:\n" << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "bad.json");
    EXPECT_EQ(e.where().json_path, c.pointer) << e.what();
    EXPECT_NE(std::string(e.what()).find(c.message_part), std::string::npos) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(SceneParser, BadInput, ::testing::ValuesIn(kBadCases),
                         [](const auto& info) { return std::string(info.param.name); });

InputError error_for(const std::string& text) {
  try {
    parse_scene_text(text, "room.json", "");
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return InputError("no error");
}

TEST(SceneParser, WhatReadsFilePointerMessage) {
  OJson scene = base_scene();
  scene["lights"][0]["intensity"] = "bright";
  EXPECT_STREQ(error_for(scene.dump()).what(),
               R"(room.json: /lights/0/intensity: expected a number or an array of 3 numbers, got "bright")");
}

TEST(SceneParser, SyntaxErrorGivesLineAndColumn) {
  const InputError e = error_for("{\n  \"camera\": {\n    \"fov\": 40,\n  }\n}\n");
  EXPECT_EQ(e.where().json_path, "");
  EXPECT_NE(std::string(e.what()).find("room.json: line 4, column 3: invalid JSON: syntax error"),
            std::string::npos)
      << e.what();
}

TEST(SceneParser, ColumnsCountCharactersNotBytes) {
  const InputError e = error_for("{\"name\": \"\xc3\xa9t\xc3\xa9\" x}");
  EXPECT_NE(std::string(e.what()).find("line 1, column 16"), std::string::npos) << e.what();
}

TEST(SceneParser, NumberOverflowIsLocated) {
  const InputError e = error_for("{\n \"camera\": {\"fov\": 1e400}}");
  EXPECT_NE(std::string(e.what()).find("line 2, column"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("number overflow"), std::string::npos) << e.what();
}

TEST(SceneParser, EmptyTextIsASyntaxError) {
  EXPECT_NE(std::string(error_for("").what()).find("line 1, column 1"), std::string::npos);
}

// ---- files and paths ----

class SceneFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = fs::temp_directory_path() / ("caligo_scene_test_" + std::to_string(::getpid()));
    fs::create_directories(dir / "assets");
  }
  void TearDown() override { fs::remove_all(dir); }
  std::string write(const std::string& name, const std::string& text) {
    std::ofstream(dir / name) << text;
    return (dir / name).string();
  }
  fs::path dir;
};

constexpr const char* kMeshScene = R"({
  "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
  "materials": {"m": {"type": "diffuse", "reflectance": 0.5}},
  "shapes": [{"type": "mesh", "file": "assets/tetra.obj", "material": "m"},
             {"type": "mesh", "file": "/abs/model.GLB", "material": "m"}]
})";

TEST_F(SceneFileTest, RelativeMeshPathsResolveAgainstTheSceneDirectory) {
  const std::string path = write("scene.json", kMeshScene);
  const SceneDesc scene = parse_scene_file(path);
  EXPECT_EQ(scene.file, path);
  EXPECT_EQ(std::get<MeshFileShape>(scene.shapes[0].geometry).path, (dir / "assets/tetra.obj").string());
  EXPECT_EQ(std::get<MeshFileShape>(scene.shapes[1].geometry).path, "/abs/model.GLB");
}

TEST_F(SceneFileTest, TextWithoutBaseDirLeavesPathsAsWritten) {
  const SceneDesc scene = parse_scene_text(kMeshScene, "x.json", "");
  EXPECT_EQ(std::get<MeshFileShape>(scene.shapes[0].geometry).path, "assets/tetra.obj");
}

TEST_F(SceneFileTest, ErrorsNameTheFileAsGiven) {
  const std::string path =
      write("bad.json", R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "fov": -1}})");
  try {
    parse_scene_file(path);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, path);
    EXPECT_EQ(e.where().json_path, "/camera/fov");
  }
}

TEST_F(SceneFileTest, MissingFileIsAnInputErrorNamingIt) {
  const std::string path = (dir / "nope.json").string();
  try {
    parse_scene_file(path);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, path);
    EXPECT_NE(std::string(e.what()).find("no such file"), std::string::npos) << e.what();
  }
}

TEST_F(SceneFileTest, DirectoryIsAnInputError) { EXPECT_THROW(parse_scene_file(dir.string()), InputError); }

#ifdef CALIGO_SOURCE_DIR
TEST(ExampleScenes, EveryFileInScenesParses) {
  int count = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(CALIGO_SOURCE_DIR) / "scenes")) {
    if (entry.path().extension() != ".json") continue;
    SCOPED_TRACE(entry.path().string());
    const SceneDesc scene = parse_scene_file(entry.path().string());
    for (const ShapeDesc& shape : scene.shapes)
      if (const auto* mesh = std::get_if<MeshFileShape>(&shape.geometry)) {
        EXPECT_TRUE(fs::exists(mesh->path)) << mesh->path;
      }
    ++count;
  }
  EXPECT_GE(count, 2);
}
#endif

}  // namespace
}  // namespace caligo

namespace caligo {
namespace {

TEST(SceneParser, MediaAndVolumes) {
  const SceneDesc scene = parse_scene_text(R"json({
    "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
    "render": {"max_volume_bounces": 1024},
    "media": {
      "fog": {"sigma_s": [0.5, 0.4, 0.3], "sigma_a": 0.1, "emission": 2, "density": 3,
              "phase": {"type": "hg", "g": 0.3}},
      "puff": {"sigma_s": 1, "falloff": {"exponent": 2}, "step_size": 0.05,
               "phase": {"type": "double_hg", "g1": 0.6, "g2": -0.2, "w": 0.8}},
      "rt": {"sigma_s": 1, "phase": {"type": "schlick", "g": 0.5}},
      "ground": {"sigma_s": 0.2, "height_falloff": {"base": 0.5, "scale_height": 3}}
    },
    "volumes": [
      {"type": "sphere", "center": [0, 1, 0], "radius": 2, "medium": "fog"},
      {"type": "box", "min": [-1, -1, -1], "max": [1, 1, 1], "medium": "puff",
       "transform": [{"translate": [0, 0, 4]}]},
      {"type": "sphere", "center": [0, 0, 0], "radius": 1, "medium": "rt"},
      {"type": "box", "min": [-9, 0, -9], "max": [9, 8, 9], "medium": "ground"}
    ]
  })json",
                                           "vol.json", "");
  EXPECT_EQ(scene.render.path.limits.max_volume_bounces, 1024);
  ASSERT_EQ(scene.volumes.size(), 4u);
  const auto& ground = std::get<HeightFalloffDensity>(scene.volumes[3].shader.field);
  EXPECT_FLOAT_EQ(ground.base, 0.5f);
  EXPECT_FLOAT_EQ(ground.scale_height, 3.0f);
  const VolumeShader& fog = scene.volumes[0].shader;
  EXPECT_EQ(fog.sigma_s, RGB(0.5f, 0.4f, 0.3f));
  EXPECT_EQ(fog.sigma_a, RGB(0.1f));
  EXPECT_EQ(fog.emission, RGB(2.0f));
  EXPECT_FLOAT_EQ(fog.density, 3.0f);
  EXPECT_FLOAT_EQ(std::get<HenyeyGreensteinPhase>(fog.phase).g, 0.3f);
  EXPECT_TRUE(is_homogeneous(fog));
  const auto& sphere = std::get<SphereVolumeShape>(scene.volumes[0].shape).sphere;
  EXPECT_NEAR(sphere.object_to_world.point({0, 1, 0}).y, 3.0f, 1e-6f);  // centre (0,1,0), radius 2

  const VolumeShader& puff = scene.volumes[1].shader;
  EXPECT_FLOAT_EQ(std::get<RadialFalloffDensity>(puff.field).exponent, 2.0f);
  EXPECT_FLOAT_EQ(puff.step_size, 0.05f);
  EXPECT_FLOAT_EQ(std::get<DoubleHenyeyGreensteinPhase>(puff.phase).w, 0.8f);
  const Bounds3 box = volume_bounds(scene.volumes[1].shape);
  EXPECT_NEAR(box.lo.z, 3.0f, 1e-6f);
  EXPECT_NEAR(box.hi.z, 5.0f, 1e-6f);
  // Schlick given by g: k = 1.55 g - 0.55 g^3.
  EXPECT_NEAR(std::get<SchlickPhase>(scene.volumes[2].shader.phase).k, 1.55f * 0.5f - 0.55f * 0.125f, 1e-6f);
}

TEST(SceneParser, BadMediaAreLocated) {
  const auto error_of = [](const std::string& media, const std::string& volumes) {
    try {
      parse_scene_text(R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]}, "media": )" + media +
                           R"(, "volumes": )" + volumes + "}",
                       "bad.json", "");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string sphere = R"([{"type": "sphere", "center": [0, 0, 0], "radius": 1, "medium": "m"}])";
  EXPECT_NE(error_of(R"({"m": {"sigma_a": [1, -1, 1]}})", sphere).find("bad.json: /media/m/sigma_a"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"m": {"phase": {"type": "hg", "g": -1}}})", sphere).find("/media/m/phase/g"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"m": {"phase": {"type": "mie"}}})", sphere).find("/media/m/phase/type"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"m": {"density": -2}})", sphere).find("/media/m/density"), std::string::npos);
  EXPECT_NE(error_of(R"({"m": {"step_size": 0}})", sphere).find("/media/m/step_size"), std::string::npos);
  EXPECT_NE(error_of(R"({"m": {"holdout": -0.5}})", sphere).find("/media/m/holdout: expected a number >= 0"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"m": {"holdout": 1e39}})", sphere).find("/media/m/holdout: expected a finite number"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"m": {"holdout": [1, 1, 1]}})", sphere).find("/media/m/holdout: expected a number"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"m": {"height_falloff": {"base": 1}}})", sphere)
                .find("/media/m/height_falloff: missing required key \"scale_height\""),
            std::string::npos)
      << error_of(R"({"m": {"height_falloff": {"base": 1}}})", sphere);
  EXPECT_NE(error_of(R"({"m": {"height_falloff": {"scale_height": 0}}})", sphere)
                .find("/media/m/height_falloff/scale_height"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"m": {"falloff": {}, "height_falloff": {"scale_height": 1}}})", sphere)
                .find("not both"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"m": {"colour": 1}})", sphere).find("/media/m/colour: unknown key"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"fog": {}})", sphere).find("/volumes/0/medium: unknown medium \"m\""),
            std::string::npos);
  EXPECT_NE(error_of(R"({"m": {}})", R"([{"type": "cone", "medium": "m"}])").find("/volumes/0/type"),
            std::string::npos);
}

}  // namespace
}  // namespace caligo

namespace caligo {
namespace {

TEST(SceneParser, GeneratedMeshShapes) {
  const auto with_mesh = [](const std::string& mesh) {
    return R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
               "materials": {"w": {"type": "diffuse", "reflectance": 0.5}},
               "shapes": [)" + mesh + "]}";
  };
  const SceneDesc s = parse_scene_text(
      with_mesh(R"({"type": "mesh", "generate": {"kind": "torus_knot", "triangles": 70000}, "material": "w"})"),
      "g.json", "");
  const auto& g = std::get<GeneratedMeshShape>(s.shapes[0].geometry);
  EXPECT_EQ(g.kind, GeneratedMeshShape::Kind::kTorusKnot);
  EXPECT_EQ(g.triangles, 70000u);
  const auto error_of = [&](const std::string& mesh) {
    try {
      parse_scene_text(with_mesh(mesh), "g.json", "");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error_of(R"({"type": "mesh", "generate": {"kind": "teapot"}, "material": "w"})")
                .find("/shapes/0/generate/kind"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"type": "mesh", "generate": {"kind": "sphere", "triangles": 1e9}, "material": "w"})")
                .find("/shapes/0/generate/triangles"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"type": "mesh", "file": "a.obj", "generate": {"kind": "sphere"}, "material": "w"})")
                .find("not both"),
            std::string::npos);
}

}  // namespace
}  // namespace caligo
