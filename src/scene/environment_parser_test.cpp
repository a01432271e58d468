// The environment light's scene keys (docs/scene-format.md, "environment"): image maps read
// through OpenImageIO (PFM and Radiance HDR written here byte by byte, so the file's row order
// pins the lat-long convention), the generated sky, map x color x radiance x strength,
// rotation, visibility, one read per file, and located errors for bad files and values.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <vector>

#include "core/math.h"
#include "lights/environment_map.h"
#include "lights/light_sample.h"
#include "lights/sky_generate.h"
#include "scene/scene_parser.h"

namespace caligo {
namespace {

namespace fs = std::filesystem;
using OJson = nlohmann::ordered_json;

// A little-endian PFM; `rows` top to bottom (the file stores them bottom to top).
void write_pfm(const fs::path& path, int w, int h, const std::vector<RGB>& rows) {
  std::ofstream f(path, std::ios::binary);
  f << "PF\n" << w << " " << h << "\n-1.0\n";
  for (int y = h - 1; y >= 0; --y)
    for (int x = 0; x < w; ++x) {
      const RGB c = rows[size_t(y * w + x)];
      const float v[3] = {c.r, c.g, c.b};
      f.write(reinterpret_cast<const char*>(v), sizeof v);
    }
}

// 64 x 32, black but for pixel (48, 8): u = 0.75, v = 0.25 at its corner, towards (+X, +Y).
std::vector<RGB> one_bright_pixel() {
  std::vector<RGB> px(64 * 32, RGB(0.0f));
  px[8 * 64 + 48] = RGB(10.0f, 20.0f, 30.0f);
  return px;
}

class EnvironmentFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = fs::temp_directory_path() / ("caligo_environment_parser_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    write_pfm(dir / "spot.pfm", 64, 32, one_bright_pixel());
    std::vector<RGB> bad(8, RGB(1.0f));
    bad[3] = RGB(std::nanf(""));
    write_pfm(dir / "nan.pfm", 4, 2, bad);
    bad[3] = RGB(kInfinity);
    write_pfm(dir / "inf.pfm", 4, 2, bad);
    bad[3] = RGB(-2.0f, 1.0f, 1.0f);
    write_pfm(dir / "negative.pfm", 4, 2, bad);
    write_pfm(dir / "square.pfm", 4, 4, std::vector<RGB>(16, RGB(0.5f)));
    std::ofstream(dir / "corrupt.exr") << "this is not an EXR file";
    std::ofstream(dir / "truncated.pfm", std::ios::binary) << "PF\n64 32\n-1.0\n" << std::string(100, '\0');
    // Radiance RGBE, flat scanlines: 4 x 2 pixels of 4.0 (mantissa 128, exponent 131).
    std::ofstream hdr(dir / "four.hdr", std::ios::binary);
    hdr << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 4\n";
    for (int i = 0; i < 8; ++i) hdr.write("\x80\x80\x80\x83", 4);
  }
  void TearDown() override { fs::remove_all(dir); }

  SceneDesc parse(const std::string& lights) {
    return parse_scene_text(R"({"camera": {"position": [0, 1, 5], "look_at": [0, 1, 0]}, "lights": )" + lights + "}",
                            "t.json", dir.string());
  }
  // The error's JSON pointer and message.
  std::pair<std::string, std::string> error(const std::string& lights) {
    try {
      parse(lights);
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().file, "t.json");
      return {e.where().json_path, e.what()};
    }
    ADD_FAILURE() << "no error for " << lights;
    return {};
  }
  fs::path dir;
};

TEST_F(EnvironmentFiles, FileMapPinsTheConvention) {
  const SceneDesc scene = parse(R"([{"type": "environment", "map": "spot.pfm"}])");
  const auto& env = std::get<EnvironmentLight>(scene.lights[0]);
  ASSERT_TRUE(env.map);
  ASSERT_EQ(env.map->width(), 64);
  ASSERT_EQ(env.map->height(), 32);
  EXPECT_EQ(env.map->pixel(48, 8), RGB(10.0f, 20.0f, 30.0f));  // rows read top to bottom
  EXPECT_EQ(env.radiance, RGB(1.0f));
  EXPECT_TRUE(env.visible);
  // The pixel's centre direction: +X and +Y, a little towards +Z.
  const Vec3 centre = latlong_to_direction({48.5f / 64.0f, 8.5f / 32.0f});
  EXPECT_GT(centre.x, 0.6f);
  EXPECT_GT(centre.y, 0.6f);
  EXPECT_NEAR(escaped_radiance(scene.lights[0], centre).b, 30.0f, 1e-3f);
  EXPECT_EQ(escaped_radiance(scene.lights[0], {-centre.x, centre.y, centre.z}), RGB(0.0f));
  // Importance sampling goes there.
  const auto s = sample_light(scene.lights[0], {}, {0.5f, 0.5f});
  ASSERT_TRUE(s);
  EXPECT_GT(dot(s->wi, centre), std::cos(radians(8.0f)));
}

TEST_F(EnvironmentFiles, ScaleRotationAndVisibility) {
  const SceneDesc scene = parse(R"([
    {"type": "environment", "map": {"file": "spot.pfm"}, "color": [1, 0.5, 0.25], "radiance": 2, "strength": 3,
     "rotation": 90, "visible": false},
    {"type": "environment", "map": "spot.pfm"},
    {"type": "environment", "radiance": 0.5, "strength": 4, "visible": false}])");
  const auto& a = std::get<EnvironmentLight>(scene.lights[0]);
  EXPECT_EQ(a.radiance, RGB(6.0f, 3.0f, 1.5f));  // color x radiance x strength
  EXPECT_NEAR(a.cos_rotation, 0.0f, 1e-6f);
  EXPECT_NEAR(a.sin_rotation, 1.0f, 1e-6f);
  EXPECT_FALSE(a.visible);
  EXPECT_EQ(a.map, std::get<EnvironmentLight>(scene.lights[1]).map);  // the file is read once
  // Turned by 90 degrees about +Y, what the map shows along +X comes from -Z.
  const Vec3 centre = latlong_to_direction({48.5f / 64.0f, 8.5f / 32.0f});
  const Vec3 turned{centre.z, centre.y, -centre.x};
  EXPECT_NEAR(escaped_radiance(scene.lights[0], turned).r, 60.0f, 1e-3f);
  const auto& c = std::get<EnvironmentLight>(scene.lights[2]);
  EXPECT_FALSE(c.map);
  EXPECT_EQ(c.radiance, RGB(2.0f));
  EXPECT_FALSE(c.visible);
}

TEST_F(EnvironmentFiles, OtherFormatsAndShapes) {
  const SceneDesc scene = parse(R"([{"type": "environment", "map": "four.hdr"},
                                    {"type": "environment", "map": "square.pfm"},
                                    {"type": "environment", "map": "negative.pfm"}])");
  const auto& hdr = std::get<EnvironmentLight>(scene.lights[0]);
  ASSERT_TRUE(hdr.map);
  EXPECT_EQ(hdr.map->width(), 4);
  EXPECT_NEAR(hdr.map->pixel(2, 1).g, 4.0f, 0.05f);
  // A square image is allowed: stretched over the sphere, its integral is still 4 pi L.
  EXPECT_NEAR(std::get<EnvironmentLight>(scene.lights[1]).map->integral().r, 2.0f * kPi, 1e-4f);
  // Negative values are clamped to 0 (as for gobos).
  EXPECT_EQ(std::get<EnvironmentLight>(scene.lights[2]).map->pixel(3, 0).r, 0.0f);
}

TEST_F(EnvironmentFiles, GeneratedSky) {
  const SceneDesc scene = parse(R"([{"type": "environment", "map": {"generate": {"kind": "sky",
      "resolution": 128, "sun_elevation": 20, "sun_azimuth": 90, "sun_size": 1}}}])");
  const auto& env = std::get<EnvironmentLight>(scene.lights[0]);
  ASSERT_TRUE(env.map);
  EXPECT_EQ(env.map->width(), 128);
  EXPECT_EQ(env.map->height(), 64);
  SkyParameters p;
  p.resolution = 128;
  p.sun_elevation = 20;
  p.sun_azimuth = 90;
  p.sun_angular_radius = 1;
  const EnvironmentMap expected = generate_sky(p);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 128; ++x) ASSERT_EQ(env.map->pixel(x, y), expected.pixel(x, y));
  EXPECT_EQ(std::get<EnvironmentLight>(parse(R"([{"type": "environment", "map": {"generate": {"kind": "sky"}}}])")
                .lights[0])
                .map->width(),
            512);  // the default resolution
}

// pbrt-v4's equal-area square: light +z is the square's centre; turned by -90 degrees about X
// it lies along world +y (the zenith of the lat-long map it is resampled to, 2n x n).
TEST_F(EnvironmentFiles, EqualAreaMapsAreResampledThroughTheirRotation) {
  std::vector<RGB> square(16 * 16, RGB(0.0f));
  for (int y = 6; y < 10; ++y)
    for (int x = 6; x < 10; ++x) square[size_t(y * 16 + x)] = RGB(4.0f);
  write_pfm(dir / "ea.pfm", 16, 16, square);
  const SceneDesc scene = parse(R"([{"type": "environment", "map": {"file": "ea.pfm", "projection": "equal_area",
      "transform": [{"rotate": {"angle": -90, "axis": [1, 0, 0]}}]}}])");
  const auto& env = std::get<EnvironmentLight>(scene.lights[0]);
  ASSERT_TRUE(env.map);
  EXPECT_EQ(env.map->width(), 32);
  EXPECT_EQ(env.map->height(), 16);
  EXPECT_NEAR(escaped_radiance(scene.lights[0], {0, 1, 0}).r, 4.0f, 1e-4f);
  EXPECT_EQ(escaped_radiance(scene.lights[0], {0, -1, 0}), RGB(0.0f));
  EXPECT_EQ(escaped_radiance(scene.lights[0], {0, 0, 1}), RGB(0.0f));
  // Without the rotation light +z stays world +z.
  const SceneDesc plain = parse(R"([{"type": "environment", "map": {"file": "ea.pfm", "projection": "equal_area"}}])");
  EXPECT_NEAR(escaped_radiance(plain.lights[0], {0, 0, 1}).r, 4.0f, 1e-4f);
  EXPECT_EQ(escaped_radiance(plain.lights[0], {0, 1, 0}), RGB(0.0f));
}

TEST_F(EnvironmentFiles, BadMapsAndValuesAreLocated) {
  struct Bad {
    std::string lights, pointer, message_part;
  };
  const Bad cases[] = {
      {R"([{"type": "environment", "map": "missing.exr"}])", "/lights/0/map", "missing.exr"},
      {R"([{"type": "environment", "map": "corrupt.exr"}])", "/lights/0/map", "cannot use the environment map"},
      {R"([{"type": "environment", "map": "truncated.pfm"}])", "/lights/0/map", "cannot use the environment map"},
      {R"([{"type": "environment", "map": "nan.pfm"}])", "/lights/0/map", "non-finite"},
      {R"([{"type": "environment", "map": "inf.pfm"}])", "/lights/0/map", "non-finite"},
      {R"([{"type": "environment", "map": {"file": "missing.exr"}}])", "/lights/0/map/file", "missing.exr"},
      {R"([{"type": "environment", "map": 3}])", "/lights/0/map", "expected"},
      {R"([{"type": "environment", "map": {"file": "spot.pfm", "generate": {"kind": "sky"}}}])", "/lights/0/map",
       "got both"},
      {R"([{"type": "environment", "map": {}}])", "/lights/0/map", "got neither"},
      {R"([{"type": "environment", "map": {"generate": {"kind": "clouds"}}}])", "/lights/0/map/generate/kind",
       "unknown kind"},
      {R"([{"type": "environment", "map": {"generate": {"kind": "sky", "resolution": 8}}}])",
       "/lights/0/map/generate/resolution", "in [16, 8192]"},
      {R"([{"type": "environment", "map": {"generate": {"kind": "sky", "sun_elevation": 95}}}])",
       "/lights/0/map/generate/sun_elevation", "in [0, 90]"},
      {R"([{"type": "environment", "map": {"generate": {"kind": "sky", "sun_size": 0}}}])",
       "/lights/0/map/generate/sun_size", "in [0.05, 10]"},
      {R"([{"type": "environment", "map": {"generate": {"kind": "sky", "turbidity": 3}}}])",
       "/lights/0/map/generate/turbidity", "unknown key"},
      {R"([{"type": "environment", "radiance": 1, "rotation": 30}])", "/lights/0/rotation", "has no \"map\""},
      {R"([{"type": "environment", "color": [1, 1, 1]}])", "/lights/0", "\"radiance\""},
      {R"([{"type": "environment", "map": "spot.pfm", "strength": -1}])", "/lights/0/strength", ">= 0"},
      {R"([{"type": "environment", "map": "spot.pfm", "visible": 1}])", "/lights/0/visible", "true or false"},
      {R"([{"type": "environment", "map": "spot.pfm", "rotation": "east"}])", "/lights/0/rotation", "number"},
      {R"([{"type": "environment", "map": {"file": "spot.pfm", "projection": "equal_area"}}])", "/lights/0/map/file",
       "is square"},
      {R"([{"type": "environment", "map": {"file": "square.pfm", "projection": "equal_area",
         "transform": [{"scale": 2}]}}])", "/lights/0/map/transform", "must be a rotation"},
      {R"([{"type": "environment", "map": {"file": "spot.pfm", "transform": [{"scale": 2}]}}])", "/lights/0/map/transform",
       "turns an equal-area map"},
      {R"([{"type": "environment", "map": {"generate": {"kind": "sky"}, "projection": "equal_area"}}])",
       "/lights/0/map/projection", "projection of an image file"},
      {R"([{"type": "environment", "map": {"file": "spot.pfm", "projection": "mercator"}}])", "/lights/0/map/projection",
       "mercator"},
  };
  for (const Bad& c : cases) {
    SCOPED_TRACE(c.lights);
    const auto [pointer, what] = error(c.lights);
    EXPECT_EQ(pointer, c.pointer) << what;
    EXPECT_NE(what.find(c.message_part), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace caligo
