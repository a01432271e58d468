// The scene-format keys of issue 6: box lights, gobos, IES profiles, range, real-time light
// options and animation, camera paths, density noise and the "realtime" block. Valid values
// arrive converted; bad ones fail with the file and JSON pointer.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/math.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "lights/gobo.h"
#include "lights/gobo_generate.h"
#include "lights/ies.h"
#include "lights/light_profile.h"
#include "scene/scene_parser.h"

namespace caligo {
namespace {

namespace fs = std::filesystem;
using OJson = nlohmann::ordered_json;

// Rotationally symmetric: 100 cd at nadir falling linearly to 0 at 180 degrees.
constexpr const char* kIes =
    "IESNA:LM-63-2002\nTILT=NONE\n1 1000 1 3 1 1 2 0 0 0\n1 1 50\n0 90 180\n0\n100 50 0\n";

class LightFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = fs::temp_directory_path() / ("caligo_light_parser_" + std::to_string(::getpid()));
    fs::create_directories(dir / "tex");
    std::ofstream(dir / "lamp.ies") << kIes;
    std::ofstream(dir / "broken.ies")
        << "IESNA:LM-63-2002\nTILT=NONE\n1 1000 1 3 1 1 2 0 0 0\n1 1 50\n0 90\n";
    // A 2x1 binary PPM: black, white (8-bit, so sRGB-decoded; 0 and 255 stay 0 and 1).
    std::ofstream ppm(dir / "tex/bars.ppm", std::ios::binary);
    ppm << "P6\n2 1\n255\n";
    const char px[6] = {0, 0, 0, char(255), char(255), char(255)};
    ppm.write(px, 6);
  }
  void TearDown() override { fs::remove_all(dir); }

  SceneDesc parse(const OJson& scene) { return parse_scene_text(scene.dump(), "t.json", dir.string()); }
  std::string error(const OJson& scene, std::string* pointer) {
    try {
      parse(scene);
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().file, "t.json");
      *pointer = e.where().json_path;
      return e.what();
    }
    ADD_FAILURE() << "no error for " << scene.dump();
    return "";
  }
  fs::path dir;
};

OJson with_lights(OJson lights) {
  return {{"camera", {{"position", {0, 1, 5}}, {"look_at", {0, 1, 0}}}}, {"lights", std::move(lights)}};
}

const OJson kSpot = OJson::parse(R"({"type": "spot", "position": [0, 4, 0], "direction": [0, -1, 0],
  "inner_angle": 20, "outer_angle": 30, "intensity": 10, "range": 12, "up": [1, 0, 1],
  "gobo": {"file": "tex/bars.ppm", "offset": [0.25, 0.5], "rotation": 90, "scroll": [0.1, 0], "spin": 45},
  "ies": {"file": "lamp.ies"}, "volumetric": {"enabled": true, "intensity": 2.5}, "shadow": false,
  "shadow_map_size": 512,
  "animation": {"interpolation": "catmull_rom",
                "keys": [{"time": 0, "position": [0, 4, 0]}, {"time": 2, "look_at": [1, 0, 0]}]}})");

const OJson kBox = OJson::parse(R"({"type": "box", "position": [0, 10, 0], "look_at": [0, 0, 0],
  "up": [0, 0, -1], "width": 4, "height": 2, "range": 9, "power": 80, "color": [1, 0.5, 0.25],
  "gobo": {"file": "tex/bars.ppm"}})");

TEST_F(LightFiles, EveryNewSpotKeyIsRead) {
  const SceneDesc scene = parse(with_lights({kSpot}));
  ASSERT_EQ(scene.lights.size(), 1u);
  ASSERT_EQ(scene.light_options.size(), 1u);
  const auto& spot = std::get<SpotLight>(scene.lights[0]);
  EXPECT_FLOAT_EQ(spot.range, 12.0f);
  // "up" made perpendicular to the direction: (1, 0, 1) / sqrt 2.
  EXPECT_NEAR(spot.up.x, std::sqrt(0.5f), 1e-6f);
  EXPECT_NEAR(spot.up.z, std::sqrt(0.5f), 1e-6f);
  EXPECT_NEAR(spot.up.y, 0.0f, 1e-6f);
  ASSERT_TRUE(spot.gobo.image);
  EXPECT_EQ(spot.gobo.image->width(), 2);
  EXPECT_EQ(spot.gobo.image->pixel(1, 0), RGB(1.0f));
  EXPECT_EQ(spot.gobo.image->pixel(0, 0), RGB(0.0f));
  EXPECT_FLOAT_EQ(spot.gobo.offset.x, 0.25f);
  EXPECT_FLOAT_EQ(spot.gobo.offset.y, 0.5f);
  EXPECT_FLOAT_EQ(spot.gobo.rotation, kPi / 2);
  EXPECT_FLOAT_EQ(spot.gobo.scroll.x, 0.1f);
  EXPECT_FLOAT_EQ(spot.gobo.spin, kPi / 4);
  ASSERT_TRUE(spot.ies.profile);
  EXPECT_EQ(spot.ies.axis, spot.direction);  // a spot aims its own profile
  EXPECT_FLOAT_EQ(spot.intensity.r, 10.0f);
  const LightOptions& o = scene.options(0);
  EXPECT_TRUE(o.volumetric);
  EXPECT_FLOAT_EQ(o.volumetric_intensity, 2.5f);
  EXPECT_FALSE(o.shadow);
  EXPECT_EQ(o.shadow_map_size, 512);
  EXPECT_EQ(o.interpolation, Interpolation::catmull_rom);
  ASSERT_EQ(o.animation.size(), 2u);
  EXPECT_EQ(*o.animation[0].position, Vec3(0, 4, 0));
  EXPECT_FALSE(o.animation[0].direction);
  // look_at in a key without a position aims from the light's own position.
  const Vec3 aim = *o.animation[1].direction;
  EXPECT_NEAR(aim.x, 1.0f / std::sqrt(17.0f), 1e-6f);
  EXPECT_NEAR(aim.y, -4.0f / std::sqrt(17.0f), 1e-6f);
  EXPECT_FLOAT_EQ(scene.duration(), 2.0f);
}

TEST_F(LightFiles, BoxLightConvertsPowerAndSharesTheGoboImage) {
  const SceneDesc scene = parse(with_lights({kBox, kSpot}));
  const auto& box = std::get<BoxLight>(scene.lights[0]);
  EXPECT_EQ(box.direction, Vec3(0, -1, 0));
  EXPECT_EQ(box.up, Vec3(0, 0, -1));
  EXPECT_FLOAT_EQ(box.half_width, 2.0f);
  EXPECT_FLOAT_EQ(box.half_height, 1.0f);
  EXPECT_FLOAT_EQ(box.range, 9.0f);
  // P = E w h: 80 W over 8 m^2, times the colour.
  EXPECT_FLOAT_EQ(box.irradiance.r, 10.0f);
  EXPECT_FLOAT_EQ(box.irradiance.g, 5.0f);
  EXPECT_FLOAT_EQ(box.irradiance.b, 2.5f);
  EXPECT_EQ(box.gobo.image, std::get<SpotLight>(scene.lights[1]).gobo.image);  // read once
  // Defaults of the real-time options.
  EXPECT_TRUE(scene.options(0).volumetric);
  EXPECT_FLOAT_EQ(scene.options(0).volumetric_intensity, 1.0f);
  EXPECT_TRUE(scene.options(0).shadow);
  EXPECT_EQ(scene.options(0).shadow_map_size, 1024);
}

TEST_F(LightFiles, BoxPowerRoundTripsWithoutAGobo) {
  OJson box = kBox;
  box.erase("gobo");
  box.erase("color");
  const SceneDesc scene = parse(with_lights({box}));
  EXPECT_NEAR(power(scene.lights[0]), 80.0f, 1e-3f);
}

// Emitted power measured independently: intensity in each direction, integrated over the
// sphere by a fine grid, must equal the "power" written in the file.
float integrate_intensity(const Light& light, Vec3 position) {
  constexpr int kCos = 800, kPhi = 400;
  double sum = 0.0;
  for (int i = 0; i < kCos; ++i) {
    const float cos_t = 1.0f - 2.0f * (i + 0.5f) / kCos;
    const float sin_t = std::sqrt(std::max(0.0f, 1.0f - cos_t * cos_t));
    for (int j = 0; j < kPhi; ++j) {
      const Vec3 w = spherical_direction(sin_t, cos_t, 2.0f * kPi * (j + 0.5f) / kPhi);
      const Vec3 receiver = position + w;  // at 1 m, radiance = intensity
      const auto a = std::visit(
          [&](const auto& l) -> std::optional<DeltaArrival> {
            using T = std::decay_t<decltype(l)>;
            if constexpr (std::is_same_v<T, PointLight> || std::is_same_v<T, SpotLight>)
              return delta_arrival(l, receiver);
            ADD_FAILURE() << "not a point or spot light";
            return std::nullopt;
          },
          light);
      if (a) sum += a->radiance.average();
    }
  }
  return float(sum * 4.0 * kPi / (double(kCos) * kPhi));
}

// "generate" instead of "file": the image is the generator's, with the defaults filled in,
// and the placement keys still apply.
TEST_F(LightFiles, SpotWithAGeneratedGobo) {
  OJson spot = kSpot;
  spot["gobo"] =
      OJson::parse(R"({"generate": {"kind": "stained_glass", "resolution": 64, "seed": 9}, "rotation": 90})");
  OJson box = kBox;
  box["gobo"] = OJson::parse(R"({"generate": {"kind": "checker"}})");
  const SceneDesc scene = parse(with_lights({spot, box}));
  const Gobo& gobo = std::get<SpotLight>(scene.lights[0]).gobo;
  ASSERT_TRUE(gobo.image);
  const GoboImage expected = generate_gobo(GoboPattern::kStainedGlass, 64, 9);
  ASSERT_EQ(gobo.image->width(), 64);
  ASSERT_EQ(gobo.image->height(), 64);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) ASSERT_EQ(gobo.image->pixel(x, y), expected.pixel(x, y));
  EXPECT_FLOAT_EQ(gobo.rotation, kPi / 2);
  const Gobo& checker = std::get<BoxLight>(scene.lights[1]).gobo;
  ASSERT_TRUE(checker.image);
  EXPECT_EQ(checker.image->width(), 256);  // the default resolution
  EXPECT_EQ(checker.image->pixel(0, 0), RGB(1.0f));
}

TEST_F(LightFiles, PowerWithAnIesProfileIsTheEmittedPower) {
  const SceneDesc scene = parse(with_lights(OJson::parse(R"([
    {"type": "point", "position": [0, 0, 0], "power": 100, "ies": {"file": "lamp.ies", "axis": [1, 0, 0]}},
    {"type": "spot", "position": [0, 0, 0], "direction": [0, 1, 0], "inner_angle": 30, "outer_angle": 60,
     "power": 100, "ies": {"file": "lamp.ies"}}])")));
  const auto& point = std::get<PointLight>(scene.lights[0]);
  EXPECT_EQ(point.ies.axis, Vec3(1, 0, 0));
  EXPECT_NEAR(point.ies.profile->mean(), 0.5f, 1e-3f);
  EXPECT_NEAR(integrate_intensity(scene.lights[0], {}), 100.0f, 0.5f);
  EXPECT_NEAR(power(scene.lights[0]), 100.0f, 1e-3f);
  EXPECT_NEAR(integrate_intensity(scene.lights[1], {}), 100.0f, 0.5f);
}

TEST_F(LightFiles, VolumetricAsABooleanAndDirectionalAnimation) {
  const SceneDesc scene = parse(with_lights(OJson::parse(R"([
    {"type": "directional", "direction": [0, -1, 0], "irradiance": 2, "volumetric": false,
     "animation": {"keys": [{"time": 0, "direction": [0, -1, 0]}, {"time": 1, "direction": [1, -1, 0]}]}},
    {"type": "quad", "corner": [0, 0, 0], "edge1": [1, 0, 0], "edge2": [0, 0, 1], "radiance": 1,
     "shadow": false}])")));
  EXPECT_FALSE(scene.options(0).volumetric);
  EXPECT_EQ(scene.options(0).interpolation, Interpolation::linear);
  ASSERT_EQ(scene.options(0).animation.size(), 2u);
  EXPECT_NEAR(scene.options(0).animation[1].direction->x, std::sqrt(0.5f), 1e-6f);
  EXPECT_FALSE(scene.options(1).shadow);
  EXPECT_EQ(scene.light_options.size(), scene.lights.size());
}

TEST_F(LightFiles, CameraPathRealtimeBlockAndNoise) {
  const SceneDesc scene = parse(OJson::parse(R"({
    "camera": {"path": {"interpolation": "catmull_rom", "keys": [
      {"time": 0, "position": [0, 1, 5], "look_at": [0, 1, 0]},
      {"time": 4, "position": [4, 1, 5], "look_at": [0, 1, 0]}]}},
    "realtime": {"scale": "half", "tile_size": 4, "samples": 32, "gather_radius": 3,
                 "gather_depth_falloff": 50, "temporal": false, "temporal_blend": 0.2,
                 "multiple_scattering_floor": 0.1, "fps": 24, "frames": 96, "gather_follow_slope": false, "environment_lights": 4, "shadow_filter": "none",
                 "low_depth": "centre", "sun_cascades": 2, "light_depth_cells": 0,
                 "froxels": {"width": 80, "height": 45, "slices": 128, "near_ratio": 64}},
    "media": {"haze": {"sigma_s": 0.1, "noise": {"scale": 0.5, "amplitude": 0.8, "wind": [1, 0, 0.5]}}},
    "volumes": [{"type": "box", "min": [-5, 0, -5], "max": [5, 5, 5], "medium": "haze"}]})"));
  // Without its own position and look_at the camera starts at the first key.
  EXPECT_EQ(scene.camera.position, Vec3(0, 1, 5));
  EXPECT_EQ(scene.camera.look_at, Vec3(0, 1, 0));
  ASSERT_EQ(scene.camera.path.size(), 2u);
  EXPECT_EQ(scene.camera.path_interpolation, Interpolation::catmull_rom);
  EXPECT_FLOAT_EQ(scene.duration(), 4.0f);
  const RealtimeSettings& rt = scene.realtime;
  EXPECT_EQ(rt.scale, 2);
  EXPECT_EQ(rt.accumulation.tile_size, 4);
  EXPECT_EQ(rt.accumulation.samples, 32);
  EXPECT_EQ(rt.gather_radius, 3);
  EXPECT_FLOAT_EQ(rt.gather_depth_falloff, 50.0f);
  EXPECT_FALSE(rt.temporal);
  EXPECT_FLOAT_EQ(rt.temporal_blend, 0.2f);
  EXPECT_FLOAT_EQ(rt.accumulation.multiple_scattering_floor, 0.1f);
  EXPECT_FLOAT_EQ(rt.fps, 24.0f);
  EXPECT_EQ(rt.frames, 96);
  EXPECT_FALSE(rt.gather_follow_slope);
  EXPECT_EQ(rt.environment_lights, 4);
  EXPECT_FALSE(rt.filter_surface_shadows);
  EXPECT_EQ(rt.low_depth, LowResolutionDepth::centre);
  EXPECT_EQ(rt.sun_cascades, 2);
  EXPECT_EQ(rt.light_depth_cells, 0);
  EXPECT_EQ(RealtimeSettings{}.low_depth, LowResolutionDepth::min_max);
  EXPECT_EQ(rt.froxels.width, 80);
  EXPECT_EQ(rt.froxels.height, 45);
  EXPECT_EQ(rt.froxels.slices, 128);
  EXPECT_FLOAT_EQ(rt.froxels.near_ratio, 64.0f);
  ASSERT_TRUE(scene.volumes[0].shader.noise);
  const NoiseModulation& n = *scene.volumes[0].shader.noise;
  EXPECT_FLOAT_EQ(n.scale, 0.5f);
  EXPECT_FLOAT_EQ(n.amplitude, 0.8f);
  EXPECT_EQ(n.wind, Vec3(1, 0, 0.5f));
}

struct Bad {
  std::string json;  // the whole scene
  const char* pointer;
  const char* message_part;
};

std::string scene_with_light(const std::string& light) {
  return R"({"camera": {"position": [0, 1, 5], "look_at": [0, 1, 0]}, "lights": [)" + light + "]}";
}
std::string spot_with(const std::string& extra) {
  return scene_with_light(R"({"type": "spot", "position": [0, 3, 0], "direction": [0, -1, 0],
    "inner_angle": 10, "outer_angle": 20, "intensity": 1, )" +
                          extra + "}");
}
std::string box_with(const std::string& extra) {
  return scene_with_light(R"({"type": "box", "position": [0, 3, 0], "direction": [0, -1, 0],
    "width": 1, "height": 1, )" +
                          extra + "}");
}
std::string camera_with(const std::string& camera) { return R"({"camera": )" + camera + "}"; }
std::string realtime_with(const std::string& block) {
  return R"({"camera": {"position": [0, 1, 5], "look_at": [0, 1, 0]}, "realtime": )" + block + "}";
}
std::string medium_with(const std::string& noise) {
  return R"({"camera": {"position": [0, 1, 5], "look_at": [0, 1, 0]},
    "media": {"fog": {"sigma_s": 1, "noise": )" +
         noise + "}}}";
}

TEST_F(LightFiles, BadValuesAreLocated) {
  const Bad cases[] = {
      {spot_with(R"("shadow_map_size": 8)"), "/lights/0/shadow_map_size", "in [16, 8192]"},
      {spot_with(R"("volumetric": "yes")"), "/lights/0/volumetric", "true or false"},
      {spot_with(R"("volumetric": {"intensity": -1})"), "/lights/0/volumetric/intensity", ">= 0"},
      {spot_with(R"("range": 0)"), "/lights/0/range", ""},
      {spot_with(R"("up": [0, 2, 0])"), "/lights/0/up", "not parallel"},
      {spot_with(R"("gobo": {"file": "missing.png"})"), "/lights/0/gobo/file", "missing.png"},
      {spot_with(R"("gobo": {"file": "lamp.ies"})"), "/lights/0/gobo/file", "cannot use the gobo image"},
      {spot_with(R"("gobo": {"file": "tex/bars.ppm", "offset": [1]})"), "/lights/0/gobo/offset",
       "array of 2 numbers"},
      {spot_with(R"("gobo": {"file": "tex/bars.ppm", "generate": {"kind": "bars"}})"), "/lights/0/gobo",
       "got both"},
      {spot_with(R"("gobo": {"rotation": 10})"), "/lights/0/gobo", "got neither"},
      {spot_with(R"("gobo": {"generate": {"kind": "stripes"}})"), "/lights/0/gobo/generate/kind",
       "unknown kind \"stripes\""},
      {spot_with(R"("gobo": {"generate": {"resolution": 64}})"), "/lights/0/gobo/generate", "\"kind\""},
      {spot_with(R"("gobo": {"generate": {"kind": "bars", "resolution": 3}})"),
       "/lights/0/gobo/generate/resolution", "in [8, 4096]"},
      {spot_with(R"("gobo": {"generate": {"kind": "bars", "resolution": 1e9}})"),
       "/lights/0/gobo/generate/resolution", "in [8, 4096]"},
      {spot_with(R"("gobo": {"generate": {"kind": "bars", "resolution": 64.5}})"),
       "/lights/0/gobo/generate/resolution", "integer"},
      {spot_with(R"("gobo": {"generate": {"kind": "bars", "seed": -1}})"), "/lights/0/gobo/generate/seed",
       "integer"},
      {spot_with(R"("gobo": {"generate": {"kind": "bars", "size": 64}})"), "/lights/0/gobo/generate/size",
       "unknown key"},
      {box_with(R"("irradiance": 1, "gobo": {"generate": {"kind": "checker", "resolution": 5000}})"),
       "/lights/0/gobo/generate/resolution", "in [8, 4096]"},
      {spot_with(R"("ies": {"file": "broken.ies"})"), "/lights/0/ies/file", "truncated"},
      {spot_with(R"("ies": {"file": "lamp.ies", "axis": [0, 1, 0]})"), "/lights/0/ies/axis", "unknown key"},
      {spot_with(R"("animation": {"keys": []})"), "/lights/0/animation/keys", "at least one key"},
      {spot_with(
           R"("animation": {"keys": [{"time": 1, "position": [0, 1, 0]}, {"time": 1, "position": [0, 2, 0]}]})"),
       "/lights/0/animation/keys/1/time", "times increase"},
      {spot_with(R"("animation": {"keys": [{"time": 1}]})"), "/lights/0/animation/keys/0",
       "a position or a direction"},
      {spot_with(R"("animation": {"interpolation": "cubic", "keys": [{"time": 0, "position": [0, 1, 0]}]})"),
       "/lights/0/animation/interpolation", "linear, catmull_rom"},
      {scene_with_light(R"({"type": "sphere", "center": [0, 0, 0], "radius": 1, "radiance": 1,
                            "animation": {"keys": [{"time": 0}]}})"),
       "/lights/0/animation", "unknown key"},
      {scene_with_light(R"({"type": "point", "position": [0, 0, 0], "intensity": 1,
                            "animation": {"keys": [{"time": 0, "direction": [0, 1, 0]}]}})"),
       "/lights/0/animation/keys/0/direction", "unknown key"},
      {box_with(R"("irradiance": 1, "width": 0)"), "/lights/0/width", ""},
      {box_with(R"("irradiance": 1, "power": 3)"), "/lights/0", "exactly one of"},
      {box_with(R"("irradiance": 1, "range": -2)"), "/lights/0/range", ""},
      {camera_with(R"({"path": {"keys": [{"time": 2, "position": [0, 0, 5], "look_at": [0, 0, 0]},
                                          {"time": 1, "position": [0, 0, 4], "look_at": [0, 0, 0]}]}})"),
       "/camera/path/keys/1/time", "times increase"},
      {camera_with(R"({"path": {"keys": [{"time": 0, "position": [0, 0, 5], "look_at": [0, 0, 5]}]}})"),
       "/camera/path/keys/0/look_at", "different from position"},
      {camera_with(R"({"path": {"keys": []}})"), "/camera/path/keys", "at least one key"},
      {camera_with(R"({"path": {"keys": [{"time": -1, "position": [0, 0, 5], "look_at": [0, 0, 0]}]}})"),
       "/camera/path/keys/0/time", ">= 0"},
      {realtime_with(R"({"scale": "eighth"})"), "/realtime/scale", "full, half, quarter"},
      {realtime_with(R"({"tile_size": 33})"), "/realtime/tile_size", "in [1, 32]"},
      {realtime_with(R"({"samples": 0})"), "/realtime/samples", "in [1, 1024]"},
      {realtime_with(R"({"gather_radius": 17})"), "/realtime/gather_radius", "in [0, 16]"},
      {realtime_with(R"({"temporal_blend": 0})"), "/realtime/temporal_blend", "in (0, 1]"},
      {realtime_with(R"({"multiple_scattering_floor": 1.5})"), "/realtime/multiple_scattering_floor",
       "in [0, 1]"},
      {realtime_with(R"({"fps": 0})"), "/realtime/fps", "> 0"},
      {realtime_with(R"({"frames": 0})"), "/realtime/frames", ""},
      {realtime_with(R"({"exposure": 1})"), "/realtime/exposure", "unknown key"},
      {medium_with(R"({"amplitude": 1.5})"), "/media/fog/noise/amplitude", "in [0, 1]"},
      {medium_with(R"({"scale": 0})"), "/media/fog/noise/scale", ""},
      {medium_with(R"({"wind": [1, 0]})"), "/media/fog/noise/wind", ""},
      {medium_with(R"({"octaves": 3})"), "/media/fog/noise/octaves", "unknown key"},
  };
  for (const Bad& c : cases) {
    SCOPED_TRACE(c.json);
    std::string pointer;
    const std::string what = error(OJson::parse(c.json), &pointer);
    EXPECT_EQ(pointer, c.pointer) << what;
    EXPECT_NE(what.find(c.message_part), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace caligo
