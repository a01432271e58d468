// The camera's projection and lens keys and the render settings' "filter" and "crop":
// accepted values and located errors, in the style of scene_parser_test.cpp.
#include <gtest/gtest.h>

#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "scene/scene_parser.h"

namespace caligo {
namespace {

using OJson = nlohmann::ordered_json;

OJson base_scene() {
  return OJson::parse(R"json({
    "camera": {"position": [0, 1, 5], "look_at": [0, 1, 0], "fov": 40},
    "render": {"spp": 4}
  })json");
}

SceneDesc parse(const OJson& scene) { return parse_scene_text(scene.dump(), "cam.json", ""); }

TEST(CameraParser, PerspectiveWithoutLensIsAPinhole) {
  const SceneDesc s = parse(base_scene());
  EXPECT_EQ(s.camera.projection, CameraProjection::perspective);
  EXPECT_EQ(s.camera.aperture_radius, 0.0f);
  EXPECT_EQ(s.camera.fstop, 0.0f);
  EXPECT_EQ(s.camera.focus_distance, 0.0f);
  EXPECT_EQ(s.render.filter.type, PixelFilterType::box);
  EXPECT_FLOAT_EQ(s.render.filter.radius, 0.5f);
  EXPECT_TRUE(s.render.crop.full());
}

TEST(CameraParser, OrthographicAndThinLensKeys) {
  OJson ortho = base_scene();
  ortho["camera"].erase("fov");
  ortho["camera"]["projection"] = "orthographic";
  ortho["camera"]["ortho_width"] = 3.5;
  const SceneDesc o = parse(ortho);
  EXPECT_EQ(o.camera.projection, CameraProjection::orthographic);
  EXPECT_FLOAT_EQ(o.camera.ortho_width, 3.5f);

  OJson lens = base_scene();
  lens["camera"]["projection"] = "perspective";
  lens["camera"]["aperture_radius"] = 0.02;
  lens["camera"]["focus_distance"] = 3;
  const SceneDesc l = parse(lens);
  EXPECT_FLOAT_EQ(l.camera.aperture_radius, 0.02f);
  EXPECT_FLOAT_EQ(l.camera.focus_distance, 3.0f);

  OJson fstop = base_scene();
  fstop["camera"]["fstop"] = 2.8;
  EXPECT_FLOAT_EQ(parse(fstop).camera.fstop, 2.8f);
}

TEST(CameraParser, FilterAndCrop) {
  OJson scene = base_scene();
  scene["render"]["filter"] = {{"type", "gaussian"}, {"radius", 2}, {"sigma", 0.7}};
  scene["render"]["crop"] = {0.25, 0.75, 0, 0.5};
  const SceneDesc s = parse(scene);
  EXPECT_EQ(s.render.filter.type, PixelFilterType::gaussian);
  EXPECT_FLOAT_EQ(s.render.filter.radius, 2.0f);
  EXPECT_FLOAT_EQ(s.render.filter.sigma, 0.7f);
  EXPECT_FLOAT_EQ(s.render.crop.x0, 0.25f);
  EXPECT_FLOAT_EQ(s.render.crop.y1, 0.5f);
  // A type without a radius gets its default.
  scene["render"]["filter"] = {{"type", "blackman_harris"}};
  EXPECT_FLOAT_EQ(parse(scene).render.filter.radius, PixelFilterDesc::default_radius(PixelFilterType::blackman_harris));
}

// pbrt's rounding: pixel columns ceil(W x0) .. ceil(W x1) - 1; adjacent crops share no pixel.
TEST(CropWindow, PixelBounds) {
  const CropWindow left{0.0f, 0.5f, 0.0f, 1.0f}, right{0.5f, 1.0f, 0.25f, 0.75f};
  const PixelBounds a = left.pixels({101, 40}), b = right.pixels({101, 40});
  EXPECT_EQ(a.min, (Vec2i{0, 0}));
  EXPECT_EQ(a.max, (Vec2i{51, 40}));
  EXPECT_EQ(b.min, (Vec2i{51, 10}));
  EXPECT_EQ(b.max, (Vec2i{101, 30}));
  EXPECT_TRUE((CropWindow{0.501f, 0.505f, 0.0f, 1.0f}.pixels({100, 100}).empty()));
  EXPECT_EQ(crop_window_problem({}), "");
}

struct BadCase {
  const char* name;
  std::function<void(OJson&)> edit;
  const char* pointer;
  const char* message_part;
};

std::ostream& operator<<(std::ostream& os, const BadCase& c) { return os << c.name; }

void make_ortho(OJson& s) {
  s["camera"].erase("fov");
  s["camera"]["projection"] = "orthographic";
  s["camera"]["ortho_width"] = 2;
}

const BadCase kBadCases[] = {
    {"UnknownProjection", [](OJson& s) { s["camera"]["projection"] = "fisheye"; }, "/camera/projection",
     R"(unknown projection "fisheye" for the camera; valid values: perspective, orthographic)"},
    {"ProjectionNotString", [](OJson& s) { s["camera"]["projection"] = 1; }, "/camera/projection",
     "expected a string, got 1"},
    {"OrthoWithoutWidth",
     [](OJson& s) {
       make_ortho(s);
       s["camera"].erase("ortho_width");
     },
     "/camera", R"(missing required key "ortho_width" in the camera)"},
    {"ZeroOrthoWidth",
     [](OJson& s) {
       make_ortho(s);
       s["camera"]["ortho_width"] = 0;
     },
     "/camera/ortho_width", "expected a number > 0, got 0"},
    {"NegativeOrthoWidth",
     [](OJson& s) {
       make_ortho(s);
       s["camera"]["ortho_width"] = -2;
     },
     "/camera/ortho_width", "expected a number > 0, got -2"},
    {"InfiniteOrthoWidth",
     [](OJson& s) {
       make_ortho(s);
       s["camera"]["ortho_width"] = 1e39;
     },
     "/camera/ortho_width", "expected a finite number"},
    {"OrthoWidthOnPerspective", [](OJson& s) { s["camera"]["ortho_width"] = 2; }, "/camera/ortho_width",
     "applies only to an orthographic camera"},
    {"FovOnOrthographic",
     [](OJson& s) {
       make_ortho(s);
       s["camera"]["fov"] = 30;
     },
     "/camera/fov", R"("fov" does not apply to an orthographic camera)"},
    {"ApertureOnOrthographic",
     [](OJson& s) {
       make_ortho(s);
       s["camera"]["aperture_radius"] = 0.1;
     },
     "/camera/aperture_radius", "does not apply to an orthographic camera"},
    {"NegativeAperture", [](OJson& s) { s["camera"]["aperture_radius"] = -0.01; }, "/camera/aperture_radius",
     "expected a number >= 0, got -0.01"},
    {"HugeAperture", [](OJson& s) { s["camera"]["aperture_radius"] = 1e40; }, "/camera/aperture_radius",
     "expected a finite number"},
    {"ZeroFstop", [](OJson& s) { s["camera"]["fstop"] = 0; }, "/camera/fstop", "expected a number > 0, got 0"},
    {"ApertureAndFstop",
     [](OJson& s) {
       s["camera"]["aperture_radius"] = 0.01;
       s["camera"]["fstop"] = 4;
     },
     "/camera", R"(expected at most one of "aperture_radius" or "fstop" in the camera, got both)"},
    {"NegativeFocus",
     [](OJson& s) {
       s["camera"]["fstop"] = 4;
       s["camera"]["focus_distance"] = -1;
     },
     "/camera/focus_distance", "expected a number > 0, got -1"},
    {"FocusWithoutAperture", [](OJson& s) { s["camera"]["focus_distance"] = 3; }, "/camera/focus_distance",
     "needs an aperture"},
    {"UnknownFilter", [](OJson& s) { s["render"]["filter"] = {{"type", "mitchell"}}; }, "/render/filter/type",
     R"(unknown type "mitchell" for a pixel filter; valid values: box, gaussian, blackman_harris)"},
    {"FilterNotObject", [](OJson& s) { s["render"]["filter"] = "gaussian"; }, "/render/filter",
     "expected a pixel filter (a JSON object)"},
    {"ZeroFilterRadius", [](OJson& s) { s["render"]["filter"] = {{"type", "box"}, {"radius", 0}}; },
     "/render/filter/radius", "expected a number in (0, 16], got 0"},
    {"SigmaOnBox", [](OJson& s) { s["render"]["filter"] = {{"type", "box"}, {"sigma", 1}}; }, "/render/filter/sigma",
     R"("sigma" applies only to a gaussian pixel filter)"},
    {"NegativeSigma", [](OJson& s) { s["render"]["filter"] = {{"type", "gaussian"}, {"sigma", -1}}; },
     "/render/filter/sigma", "expected a number in (0, 16], got -1"},
    {"CropNotFour", [](OJson& s) { s["render"]["crop"] = {0, 1}; }, "/render/crop",
     "expected an array of 4 numbers [x0, x1, y0, y1], got [0,1]"},
    {"CropOutOfRange", [](OJson& s) { s["render"]["crop"] = {0, 1.5, 0, 1}; }, "/render/crop/1",
     "expected a number in [0, 1], got 1.5"},
    {"CropReversed", [](OJson& s) { s["render"]["crop"] = {0.6, 0.4, 0, 1}; }, "/render/crop",
     "expected x0 < x1, got [0.6,0.4,0,1]"},
    {"CropEmptyInY", [](OJson& s) { s["render"]["crop"] = {0, 1, 0.5, 0.5}; }, "/render/crop",
     "expected y0 < y1"},
};

class CameraBadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(CameraBadInput, NamesPointerAndProblem) {
  const BadCase& c = GetParam();
  OJson scene = base_scene();
  c.edit(scene);
  const std::string text = scene.dump(2);
  try {
    parse_scene_text(text, "bad.json", "");
    FAIL() << "no error for:\n" << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "bad.json");
    EXPECT_EQ(e.where().json_path, c.pointer) << e.what();
    EXPECT_NE(std::string(e.what()).find(c.message_part), std::string::npos) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(CameraParser, CameraBadInput, ::testing::ValuesIn(kBadCases),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace caligo
