// End-to-end tests of the caligo binary: what a user sees (exit codes, messages, files).
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "cli_testing.h"
#include "image/exr_io.h"

namespace {

using namespace caligo_cli;

class Cli : public CliFixture {};

TEST_F(Cli, VersionAndHelp) {
  const RunResult v = run("--version");
  EXPECT_EQ(v.exit_code, 0);
  EXPECT_NE(v.out.find("caligo "), std::string::npos);
  const RunResult h = run("--help");
  EXPECT_EQ(h.exit_code, 0);
  EXPECT_NE(h.out.find("render"), std::string::npos);
  EXPECT_NE(h.out.find("compare"), std::string::npos);
}

TEST_F(Cli, ListsBuiltins) {
  const RunResult r = run("render --list-builtins");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("default"), std::string::npos);
}

// `scene show` prints a built-in's JSON: saved and rendered as a file, it gives the built-in's
// own pixels, bit for bit; `scene list` names every built-in; an unknown name exits 2.
TEST_F(Cli, SceneShowPrintsABuiltinThatRendersToTheSameBits) {
  const RunResult list = run("scene list");
  EXPECT_EQ(list.exit_code, 0);
  EXPECT_NE(list.out.find("lamp-in-fog"), std::string::npos) << list.out;
  const RunResult shown = run("scene show lamp-in-fog");
  ASSERT_EQ(shown.exit_code, 0) << shown.err;
  const fs::path scene = dir_ / "mine.json", a = dir_ / "builtin.exr", b = dir_ / "file.exr";
  std::ofstream(scene) << shown.out;
  ASSERT_EQ(run("render lamp-in-fog --res 16x12 --spp 4 -q -o " + a.string()).exit_code, 0);
  const RunResult file = run("render " + scene.string() + " --res 16x12 --spp 4 -q -o " + b.string());
  ASSERT_EQ(file.exit_code, 0) << file.err;
  const RunResult same = run("compare " + a.string() + " " + b.string() + " --max-rmse 0");
  EXPECT_EQ(same.exit_code, 0) << same.out;
  const RunResult unknown = run("scene show lamp-in-smog");
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_NE(unknown.err.find("no built-in called \"lamp-in-smog\""), std::string::npos) << unknown.err;
}

// A pbrt-v4 scene and the same scene written in Caligo's JSON render to the same bits; a
// pbrt directive Caligo cannot render exits 2 naming the file and line, and writes nothing.
TEST_F(Cli, APbrtSceneRendersAsItsJsonTwinAndRefusesWhatItCannotRender) {
  const std::string dir = std::string(CALIGO_SOURCE_DIR) + "/scenes/pbrt/";
  const fs::path a = dir_ / "pbrt.exr", b = dir_ / "json.exr", bad = dir_ / "bad.exr";
  const RunResult from_pbrt = run("render " + dir + "wuson-in-haze.pbrt --res 40x30 --spp 2 -q -o " + a.string());
  ASSERT_EQ(from_pbrt.exit_code, 0) << from_pbrt.err;
  EXPECT_NE(from_pbrt.err.find("wuson-in-haze.pbrt:20: Material \"coateddiffuse\": approximated"), std::string::npos)
      << from_pbrt.err;
  ASSERT_EQ(run("render " + dir + "wuson-in-haze.json --res 40x30 --spp 2 -q -o " + b.string()).exit_code, 0);
  const RunResult same = run("compare " + a.string() + " " + b.string() + " --max-rmse 0");
  EXPECT_EQ(same.exit_code, 0) << same.out;
  const fs::path scene = dir_ / "cylinder.pbrt";
  std::ofstream(scene) << "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\"\nWorldBegin\n\nShape \"cylinder\"\n";
  const RunResult r = run("render " + scene.string() + " -q -o " + bad.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("cylinder.pbrt:5: Shape \"cylinder\" cannot be rendered"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(bad));
}

// --secondary chooses the estimator of segments after the first bounce: march and the default
// (auto) render a homogeneous scene to the same bits; an unknown value exits 2 before rendering,
// naming the option, and writes nothing.
TEST_F(Cli, SecondaryOptionKeepsHomogeneousScenesAndRefusesUnknownValues) {
  const fs::path a = dir_ / "march.exr", b = dir_ / "auto.exr", bad = dir_ / "bad.exr";
  ASSERT_EQ(run("render lamp-in-fog --res 16x12 --spp 4 -q --secondary march -o " + a.string()).exit_code, 0);
  ASSERT_EQ(run("render lamp-in-fog --res 16x12 --spp 4 -q -o " + b.string()).exit_code, 0);
  const RunResult same = run("compare " + a.string() + " " + b.string() + " --max-rmse 0");
  EXPECT_EQ(same.exit_code, 0) << same.out;
  const RunResult r = run("render lamp-in-fog --res 16x12 --spp 4 -q --secondary sideways -o " + bad.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--secondary"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(bad));
}

// The RMSE `caligo compare` prints on its first line.
double printed_rmse(const RunResult& r) {
  double rmse = -1.0;
  if (std::sscanf(r.out.c_str(), "rmse %lf", &rmse) != 1) ADD_FAILURE() << "no rmse in: " << r.out;
  return rmse;
}

// --frames renders a VDB sequence: "{frame:04}" in the scene's grid names and in -o become each
// frame's number, each frame is its own complete output; a pattern without --frames, and a
// sequence whose -o has no pattern (every frame would overwrite the last), exit 2 writing nothing.
TEST_F(Cli, FramesRenderAGridSequenceIntoOneOutputPerFrame) {
  for (int f : {3, 4})
    ASSERT_EQ(run("generate smoke -o " + (dir_ / ("puff_000" + std::to_string(f) + ".vdb")).string() + " --res 16 --seed " +
                  std::to_string(f) + " -q").exit_code, 0);
  const fs::path scene = dir_ / "seq.json";
  std::ofstream(scene) << R"({"camera": {"position": [0, 1, 4], "look_at": [0, 0.5, 0], "resolution": [16, 12]},
    "render": {"spp": 1}, "media": {"smoke": {"albedo": 0.8, "extinction": 5}},
    "volumes": [{"type": "vdb", "file": "puff_{frame:04}.vdb", "medium": "smoke"}],
    "lights": [{"type": "directional", "direction": [0.3, -1, -0.2], "irradiance": 3}]})";
  const RunResult r = run("render " + scene.string() + " --frames 3..4 -q -o " + (dir_ / "f_{frame}.exr").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_TRUE(fs::exists(dir_ / "f_3.exr") && fs::exists(dir_ / "f_4.exr") && fs::exists(dir_ / "f_4.png"));
  // Two different grids: two different pictures.
  EXPECT_GT(printed_rmse(run("compare " + (dir_ / "f_3.exr").string() + " " + (dir_ / "f_4.exr").string())), 0.0);
  const RunResult no_frames = run("render " + scene.string() + " -q -o " + (dir_ / "g.exr").string());
  EXPECT_EQ(no_frames.exit_code, 2);
  EXPECT_NE(no_frames.err.find("/volumes/0/file: the file name has a {frame} pattern"), std::string::npos) << no_frames.err;
  const RunResult overwrite = run("render " + scene.string() + " --frames 3..4 -q -o " + (dir_ / "g.exr").string());
  EXPECT_EQ(overwrite.exit_code, 2);
  EXPECT_NE(overwrite.err.find("has no {frame} pattern"), std::string::npos) << overwrite.err;
  EXPECT_FALSE(fs::exists(dir_ / "g.exr"));
  EXPECT_EQ(run("render " + scene.string() + " --frames 4..3 -q").exit_code, 2);
}

// Two renders with different seeds differ by noise alone: per pixel and channel their
// difference has variance 2 sigma^2 / spp, so their RMSE is sqrt(2 / spp) sigma-bar and falls
// by 2 from 16 to 64 spp. The noise is measured at 16 spp (seeds 1 and 2, `rmse16`); two
// 64 spp renders (seeds 3 and 4) must then agree within --max-rmse 0.75 rmse16, 1.5 times
// the predicted rmse16 / 2 (over 10 seed pairs the RMSE of `default` at 32x32 spread by
// +-15 % at 16 and 64 spp; measured here 0.101 and 0.055). The same threshold must reject a
// render without indirect light (--max-depth 1, RMSE 0.14) and another built-in (0.9).
TEST_F(Cli, RendersABuiltinTwiceAndComparesTheRenders) {
  const auto render = [&](const std::string& name, int spp, int seed, const std::string& extra = "") {
    const fs::path exr = dir_ / (name + ".exr");
    const RunResult r = run("render " + extra + " --res 32x32 --spp " + std::to_string(spp) + " --seed " +
                            std::to_string(seed) + " -q -o " + exr.string());
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(fs::exists(exr));
    EXPECT_TRUE(fs::exists(dir_ / (name + ".png")));
    return exr.string();
  };
  const std::string a16 = render("a16", 16, 1, "default"), b16 = render("b16", 16, 2, "default");
  const RunResult noise = run("compare " + a16 + " " + b16);
  ASSERT_EQ(noise.exit_code, 0) << noise.err;
  const double rmse16 = printed_rmse(noise);
  ASSERT_GT(rmse16, 0.0) << "different seeds gave the same image";

  const std::string max_rmse = " --max-rmse " + std::to_string(0.75 * rmse16);
  const std::string a64 = render("a64", 64, 3, "default"), b64 = render("b64", 64, 4, "default");
  const RunResult same = run("compare " + a64 + " " + b64 + max_rmse);
  EXPECT_EQ(same.exit_code, 0) << same.out << same.err;
  const double rmse64 = printed_rmse(same);
  std::printf("default 32x32: rmse %.4f at 16 spp, %.4f at 64 spp (threshold %.4f)\n", rmse16, rmse64,
              0.75 * rmse16);
  EXPECT_GT(rmse64, 0.25 * rmse16) << "64 spp renders with different seeds should still differ";

  const std::string direct = render("direct", 64, 3, "default --max-depth 1");
  const RunResult no_indirect = run("compare " + direct + " " + b64 + max_rmse);
  EXPECT_EQ(no_indirect.exit_code, 4) << no_indirect.out;
  EXPECT_NE(no_indirect.err.find("exceeds"), std::string::npos) << no_indirect.err;
  const std::string other = render("other", 16, 1, "lights-showcase");
  const RunResult different = run("compare " + other + " " + b64 + max_rmse);
  EXPECT_EQ(different.exit_code, 4) << different.out;
  std::printf("rmse against the 64 spp render: --max-depth 1 %.4f, lights-showcase %.4f\n",
              printed_rmse(no_indirect), printed_rmse(different));
}

TEST_F(Cli, SameSeedGivesTheSameImageOnOneAndTwoThreads) {
  const fs::path one = dir_ / "one.exr", two = dir_ / "two.exr", other = dir_ / "other.exr";
  ASSERT_EQ(run("render default --res 32x32 --spp 4 -q --threads 1 -o " + one.string()).exit_code, 0);
  ASSERT_EQ(run("render default --res 32x32 --spp 4 -q --threads 2 -o " + two.string()).exit_code, 0);
  const RunResult same = run("compare " + one.string() + " " + two.string());
  EXPECT_EQ(same.exit_code, 0);
  EXPECT_NE(same.out.find("max_abs_difference 0\n"), std::string::npos) << same.out;

  ASSERT_EQ(run("render default --res 32x32 --spp 4 -q --seed 7 -o " + other.string()).exit_code, 0);
  const RunResult differ = run("compare " + one.string() + " " + other.string() + " --max-rmse 1e-9");
  EXPECT_EQ(differ.exit_code, 4);
  EXPECT_NE(differ.err.find("exceeds"), std::string::npos);
}

TEST_F(Cli, SummaryLineReportsThroughput) {
  const RunResult r = run("render default --res 16x16 --spp 2 -o " + (dir_ / "s.exr").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("paths/s"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("rays/s"), std::string::npos) << r.err;
}

// --- Bad input: one line naming the file and the JSON path, exit code 2, no output. ---

const char* kValidScene = R"({
  "camera": {"position": [0, 1, 4], "look_at": [0, 1, 0], "fov": 40, "resolution": [16, 16]},
  "render": {"spp": 1},
  "materials": {"white": {"type": "diffuse", "reflectance": 0.5}},
  "shapes": [SHAPE],
  "lights": [{"type": "point", "position": [0, 2, 0], "intensity": 5}]
})";

std::string scene_with(const std::string& needle, const std::string& replacement,
                       const std::string& shape =
                           R"({"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "white"})") {
  std::string s = kValidScene;
  s.replace(s.find("SHAPE"), 5, shape);
  if (!needle.empty()) {
    const size_t at = s.find(needle);
    EXPECT_NE(at, std::string::npos) << needle;
    s.replace(at, needle.size(), replacement);
  }
  return s;
}

struct BadCase {
  const char* name;
  std::string scene;
  std::string expected;  // must appear in the one-line error
};

TEST_F(Cli, BadScenesGiveLocatedErrorsAndNoOutput) {
  const std::vector<BadCase> cases = {
      {"syntax", scene_with("\"render\"", "\"render\" ::"), "line 3"},
      {"unknown_key", scene_with("\"fov\"", "\"colour\": 1, \"fov\""),
       "/camera/colour: unknown key \"colour\""},
      {"wrong_type", scene_with("\"intensity\": 5", "\"intensity\": \"bright\""), "/lights/0/intensity"},
      {"missing_key", scene_with("\"position\": [0, 2, 0], ", ""), "/lights/0"},
      {"not_finite",
       scene_with("", "", R"({"type": "sphere", "center": [0, 0, 0], "radius": 1e39, "material": "white"})"),
       "/shapes/0/radius"},
      {"negative_radius",
       scene_with("", "", R"({"type": "sphere", "center": [0, 0, 0], "radius": -1, "material": "white"})"),
       "/shapes/0/radius"},
      {"zero_box",
       scene_with("", "", R"({"type": "box", "min": [0,0,0], "max": [1,0,1], "material": "white"})"),
       "/shapes/0"},
      {"absurd_resolution", scene_with("[16, 16]", "[100000, 16]"), "/camera/resolution"},
      {"too_many_pixels", scene_with("[16, 16]", "[16384, 8192]"),
       "/camera/resolution: resolution 16384x8192"},
      {"zero_spp", scene_with("\"spp\": 1", "\"spp\": 0"), "/render/spp"},
      {"unknown_material",
       scene_with("", "", R"({"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "chrome"})"),
       "/shapes/0/material"},
      {"unknown_light_type", scene_with("\"type\": \"point\"", "\"type\": \"laser\""), "/lights/0/type"},
      {"missing_mesh", scene_with("", "", R"({"type": "mesh", "file": "nowhere.obj", "material": "white"})"),
       "nowhere.obj"},
      {"nan_mesh", scene_with("", "", R"({"type": "mesh", "file": "nan.obj", "material": "white"})"),
       "non-finite"},
      {"degenerate_mesh", scene_with("", "", R"({"type": "mesh", "file": "flat.obj", "material": "white"})"),
       "degenerate"},
      {"negative_colour", scene_with("\"reflectance\": 0.5", "\"reflectance\": [0.5, -0.1, 0.5]"),
       "/materials/white/reflectance"},
      {"top_level_key", scene_with("\"render\"", "\"fog\": [], \"render\""), "unknown key \"fog\""},
      {"negative_sigma", scene_with("\"render\"", R"("media": {"m": {"sigma_s": -1}}, "render")"),
       "/media/m/sigma_s"},
      {"unknown_phase",
       scene_with("\"render\"", R"("media": {"m": {"phase": {"type": "rayleigh"}}}, "render")"),
       "/media/m/phase/type"},
      {"g_out_of_range",
       scene_with("\"render\"", R"("media": {"m": {"phase": {"type": "hg", "g": 1}}}, "render")"),
       "/media/m/phase/g"},
      {"unknown_medium",
       scene_with(
           "\"render\"",
           R"("volumes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "medium": "mist"}], "render")"),
       "/volumes/0/medium"},
  };
  write("nan.obj", "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n");
  write("flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
  for (const BadCase& c : cases) {
    const fs::path scene = write(std::string(c.name) + ".json", c.scene);
    const fs::path exr = dir_ / "out.exr";
    const RunResult r = run("render " + scene.string() + " -q -o " + exr.string());
    EXPECT_EQ(r.exit_code, 2) << c.name << ": " << r.err;
    EXPECT_EQ(r.err.rfind("caligo: error: " + scene.string(), 0), 0u) << c.name << ": " << r.err;
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << c.name << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << c.name << ": " << r.err;
    EXPECT_TRUE(outputs().empty()) << c.name;
  }
}

TEST_F(Cli, AFailedRenderLeavesAnExistingOutputUntouched) {
  const fs::path exr = write("keep.exr", "precious");
  const fs::path scene = write("bad.json", scene_with("\"spp\": 1", "\"spp\": -3"));
  EXPECT_EQ(run("render " + scene.string() + " -q -o " + exr.string()).exit_code, 2);
  EXPECT_EQ(slurp(exr), "precious");
}

TEST_F(Cli, BadCommandLinesExitWithTwo) {
  const fs::path exr = dir_ / "x.exr";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"render default --res 10 -o " + exr.string(), "--res"},
      {"render default --res 0x10 -o " + exr.string(), "--res"},
      {"render default --spp 0 -o " + exr.string(), "--spp"},
      {"render default --res 16384x16384 -o " + exr.string(), "at most"},
      {"render default --threads banana -o " + exr.string(), "--threads"},
      {"render no-such-scene -o " + exr.string(), "no-such-scene"},
      {"render default -o " + (dir_ / "missing-dir" / "x.exr").string(), "does not exist"},
      {"render default -o " + (dir_ / "x.tiff").string(), ".exr"},
      {"compare " + (dir_ / "nope.exr").string() + " " + (dir_ / "nope.exr").string(), "nope.exr"},
      {"frobnicate", "unknown command \"frobnicate\""},
      {"render default --guiding sometimes -o " + exr.string(), "--guiding: expected off, surface, volume or all"},
      {"render default --adaptive-threshold 0 -o " + exr.string(), "--adaptive-threshold"},
      {"render default --adaptive-threshold 2 -o " + exr.string(), "--adaptive-threshold"},
      {"render default --adaptive-min-samples 8 -o " + exr.string(), "needs --adaptive-threshold"},
      {"render default --clamp-indirect -1 -o " + exr.string(), "--clamp-indirect"},
      {"render default --clamp-direct nan -o " + exr.string(), "--clamp-direct"},
  };
  for (const auto& [args, expected] : cases) {
    const RunResult r = run(args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.err;
    EXPECT_EQ(r.err.rfind("caligo: error: ", 0), 0u) << args << ": " << r.err;
    EXPECT_NE(r.err.find(expected), std::string::npos) << args << ": " << r.err;
    EXPECT_TRUE(outputs().empty()) << args;
  }
}

// --aov all writes every output as EXR channels; the light layers add up to the beauty in each
// pixel (up to float rounding of the resolve), and alpha is a coverage in [0, 1].
TEST_F(Cli, AovAllWritesEveryLayer) {
  const fs::path exr = dir_ / "aovs.exr";
  const RunResult r = run("render default --res 12x8 --spp 2 --aov all -q -o " + exr.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_TRUE(fs::exists(dir_ / "aovs.png"));
  const caligo::Image image = caligo::read_exr(exr.string());
  std::vector<std::string> expected = {"R", "G", "B", "A", "Z", "N.X", "N.Y", "N.Z", "albedo.R", "albedo.G",
                                       "albedo.B"};
  const std::vector<std::string> layers = {"surface_direct",   "surface_indirect", "volume_direct",
                                           "volume_indirect",  "surface_emission", "volume_emission",
                                           "background"};
  for (const std::string& l : layers)
    for (const char* c : {".R", ".G", ".B"}) expected.push_back(l + c);
  for (const std::string& name : expected) EXPECT_TRUE(image.has_channel(name)) << name;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      const float a = image.at(x, y, image.channel_index("A"));
      EXPECT_TRUE(a >= 0.0f && a <= 1.0f) << x << "," << y << ": " << a;
      for (const char* c : {"R", "G", "B"}) {
        double sum = 0.0;
        for (const std::string& l : layers) sum += image.at(x, y, image.channel_index(l + "." + c));
        const float beauty = image.at(x, y, image.channel_index(c));
        EXPECT_NEAR(sum, beauty, 1e-5 * (1.0 + std::abs(beauty))) << x << "," << y << " " << c;
      }
    }
  // The default is the beauty with alpha, depth, normal and albedo; "volume.direct" is the dotted
  // spelling of volume_direct.
  const fs::path small = dir_ / "small.exr";
  ASSERT_EQ(run("render lamp-in-fog --res 4x4 --spp 1 --aov alpha,volume.direct -q -o " + small.string()).exit_code, 0);
  EXPECT_EQ(caligo::read_exr(small.string()).channels(),
            (std::vector<std::string>{"R", "G", "B", "A", "volume_direct.R", "volume_direct.G", "volume_direct.B"}));
}

// A bad --aov entry is a command-line error that names it, before anything is rendered.
TEST_F(Cli, BadAovIsAnInputError) {
  const fs::path exr = dir_ / "x.exr";
  for (const std::string& list : std::vector<std::string>{"bogus", "alpha,bogus", "alpha,,depth"}) {
    const RunResult r = run("render default --res 8x8 --spp 1 --aov " + list + " -o " + exr.string());
    EXPECT_EQ(r.exit_code, 2) << list << ": " << r.err;
    EXPECT_EQ(r.err.rfind("caligo: error: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find("--aov"), std::string::npos) << r.err;
    if (list != "alpha,,depth") {
      EXPECT_NE(r.err.find("'bogus'"), std::string::npos) << r.err;
    }
    EXPECT_TRUE(outputs().empty()) << list;
  }
}

// --priority MATERIAL=LEVEL changes a medium-bounding material's priority before the build:
// priority-cubes rendered both ways differs (the overlap turns from red to green).
TEST_F(Cli, PriorityOverrideChangesTheImage) {
  const fs::path red = dir_ / "red.exr", green = dir_ / "green.exr", same = dir_ / "same.exr";
  const std::string base = "render priority-cubes --res 24x16 --spp 2 -q ";
  ASSERT_EQ(run(base + "-o " + red.string()).exit_code, 0);
  const RunResult g = run(base + "--priority green=very_high --priority red=200 -o " + green.string());
  ASSERT_EQ(g.exit_code, 0) << g.err;
  ASSERT_EQ(run(base + "--priority red=high -o " + same.string()).exit_code, 0);
  EXPECT_EQ(run("compare " + red.string() + " " + same.string() + " --max-rmse 0").exit_code, 0);
  EXPECT_EQ(run("compare " + red.string() + " " + green.string() + " --max-rmse 1e-9").exit_code, 4);

  const fs::path exr = dir_ / "x.exr";
  for (const auto& [args, expected] : std::vector<std::pair<std::string, std::string>>{
           {"--priority blue=high", "\"blue\" is not a material that bounds a medium (they are: red, green)"},
           {"--priority ground=high", "\"ground\" is not a material that bounds a medium"},
           {"--priority green=highest", "expected a level (off, very_high, high, normal, low, very_low"},
           {"--priority green=-5", "expected a level"},
           {"--priority green=100001", "expected a level"},
           {"--priority green=off", "has an interior medium, so its priority cannot be off"},
           {"--priority green", "expected MATERIAL=LEVEL"},
       }) {
    const RunResult r = run("render priority-cubes -q " + args + " -o " + exr.string());
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.err;
    EXPECT_NE(r.err.find("--priority"), std::string::npos) << args << ": " << r.err;
    EXPECT_NE(r.err.find(expected), std::string::npos) << args << ": " << r.err;
    EXPECT_FALSE(fs::exists(exr)) << args;
  }
}

// --light-sampler: the three strategies render; power and tree make different images of a
// scene with many lights (two lights and a sky in `default`); anything else is exit 2.
TEST_F(Cli, LightSamplerOption) {
  const fs::path tree = dir_ / "tree.exr", power = dir_ / "power.exr", uniform = dir_ / "uniform.exr";
  const std::string base = "render default --res 24x16 --spp 2 -q ";
  ASSERT_EQ(run(base + "-o " + tree.string()).exit_code, 0);
  ASSERT_EQ(run(base + "--light-sampler power -o " + power.string()).exit_code, 0);
  ASSERT_EQ(run(base + "--light-sampler uniform -o " + uniform.string()).exit_code, 0);
  const fs::path explicit_tree = dir_ / "tree2.exr";
  ASSERT_EQ(run(base + "--light-sampler tree -o " + explicit_tree.string()).exit_code, 0);
  EXPECT_EQ(run("compare " + tree.string() + " " + explicit_tree.string() + " --max-rmse 0").exit_code, 0);
  EXPECT_EQ(run("compare " + tree.string() + " " + power.string() + " --max-rmse 1e-9").exit_code, 4);
  const fs::path bad = dir_ / "bad.exr";
  const RunResult r = run(base + "--light-sampler bvh -o " + bad.string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--light-sampler: expected tree, power, uniform or tree-fixed-share, got \"bvh\""), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(bad));
}

// --max-bounces and its alias --max-depth set the same limit: the same image bit for bit, and a
// different one with one bounce more (`default` has walls that light each other); both is exit 2.
TEST_F(Cli, MaxBouncesAndItsAlias) {
  const fs::path bounces = dir_ / "bounces.exr", depth = dir_ / "depth.exr", more = dir_ / "more.exr";
  const std::string base = "render default --res 24x16 --spp 2 -q ";
  ASSERT_EQ(run(base + "--max-bounces 1 -o " + bounces.string()).exit_code, 0);
  ASSERT_EQ(run(base + "--max-depth 1 -o " + depth.string()).exit_code, 0);
  ASSERT_EQ(run(base + "--max-bounces 2 -o " + more.string()).exit_code, 0);
  EXPECT_EQ(run("compare " + bounces.string() + " " + depth.string() + " --max-rmse 0").exit_code, 0);
  EXPECT_EQ(run("compare " + bounces.string() + " " + more.string() + " --max-rmse 1e-9").exit_code, 4);
  const fs::path bad = dir_ / "bad.exr";
  const RunResult both = run(base + "--max-bounces 1 --max-depth 2 -o " + bad.string());
  EXPECT_EQ(both.exit_code, 2) << both.err;
  EXPECT_NE(both.err.find("--max-bounces"), std::string::npos) << both.err;
  const RunResult negative = run(base + "--max-depth -1 -o " + bad.string());
  EXPECT_EQ(negative.exit_code, 2) << negative.err;
  EXPECT_FALSE(fs::exists(bad));
}

}  // namespace

// ---- caligo realtime ----

const char* kSmallRealtimeScene = R"({
  "camera": {"position": [0, 1.5, 5], "look_at": [0, 1, 0], "resolution": [64, 48],
             "path": {"keys": [{"time": 0, "position": [0, 1.5, 5], "look_at": [0, 1, 0]},
                               {"time": 1, "position": [1, 1.5, 5], "look_at": [0, 1, 0]}]}},
  "materials": {"grey": {"type": "diffuse", "reflectance": 0.5}},
  "shapes": [{"type": "rectangle", "corner": [-4, 0, -4], "edge1": [0, 0, 8], "edge2": [8, 0, 0], "material": "grey"}],
  "lights": [{"type": "spot", "position": [0, 3, 0], "look_at": [0, 0, 0], "inner_angle": 15, "outer_angle": 25,
              "intensity": 20}],
  "media": {"fog": {"sigma_s": 0.2}},
  "volumes": [{"type": "box", "min": [-4, 0, -4], "max": [4, 4, 4], "medium": "fog"}]
})";

TEST_F(Cli, RealtimeWritesFramesAndPrintsThePassTable) {
  const fs::path scene = write("rt.json", kSmallRealtimeScene);
  const RunResult r = run("realtime " + scene.string() + " --frames 4 --warmup 1 -o " + (dir_ / "frames").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (int i = 0; i < 4; ++i) EXPECT_TRUE(fs::exists(dir_ / "frames" / ("frame_000" + std::to_string(i) + ".png")));
  for (const char* pass : {"depth", "shadow maps", "accumulation", "light 0 (spot, march)", "gather", "upsample",
                           "temporal", "composite", "total"})
    EXPECT_NE(r.out.find(pass), std::string::npos) << pass;
  EXPECT_NE(r.out.find("caligo realtime:"), std::string::npos);
}

TEST_F(Cli, RealtimeWritesAnAnimatedGif) {
  const fs::path scene = write("rt.json", kSmallRealtimeScene);
  const RunResult r = run("realtime " + scene.string() + " --frames 3 -q -o " + (dir_ / "anim.gif").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_GT(fs::file_size(dir_ / "anim.gif"), 100u);
}

TEST_F(Cli, RealtimeComparesWithTheReference) {
  const fs::path scene = write("rt.json", kSmallRealtimeScene);
  const RunResult r = run("realtime " + scene.string() + " --frames 2 -q --reference-spp 16 --compare-reference -o " +
                          (dir_ / "last.png").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "last.comparison.png"));
  // The figures the comparison prints. Measured (2026-12): mean error -1.74 % and relative RMSE
  // 12.05 % at 16 spp; -1.54 % and 11.97 % at 64 spp, so the frame's own bias is about -1.5 % and
  // its per-pixel error about 12 %. Held within 3 % and 15 %.
  double mean_error = 0.0, relative_rmse = 0.0;
  const size_t at = r.out.find("mean error ");
  ASSERT_NE(at, std::string::npos) << r.out;
  ASSERT_EQ(std::sscanf(r.out.c_str() + at, "mean error %lf %%, relative RMSE %lf %%", &mean_error, &relative_rmse), 2)
      << r.out;
  EXPECT_LT(std::abs(mean_error), 3.0);
  EXPECT_GT(relative_rmse, 6.0);  // the frame's own per-pixel error is about 12 %
  EXPECT_LT(relative_rmse, 15.0);
}

TEST_F(Cli, RealtimeRejectsBadOptionsBeforeRendering) {
  const fs::path scene = write("rt.json", kSmallRealtimeScene);
  for (const std::string& bad : {std::string("--scale eighth"), std::string("--frames 0"), std::string("--samples 0"),
                                 std::string("--ms-floor 2"), std::string("--method magic"),
                                 std::string("--scene-buffers gpu"), std::string("--res 0x10"),
                                 std::string("--steps diagonal"), std::string("--time nan"),
                                 std::string("--spot-model sun"), std::string("--froxels 160x90"),
                                 std::string("--froxels 0x90x64"), std::string("--froxels 1024x1024x512")}) {
    const RunResult r = run("realtime " + scene.string() + " " + bad);
    EXPECT_EQ(r.exit_code, 2) << bad;
    EXPECT_NE(r.err.find("caligo: error: command line"), std::string::npos) << bad << ": " << r.err;
  }
  const RunResult missing = run("realtime " + scene.string() + " -o " + (dir_ / "no" / "such" / "x.gif").string());
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("does not exist"), std::string::npos);
  // A grid without the method that uses it: said, not silently ignored.
  const RunResult unused = run("realtime " + scene.string() + " --froxels 80x45x32 --frames 1 -q");
  EXPECT_EQ(unused.exit_code, 0) << unused.err;
  EXPECT_NE(unused.err.find("warning: --froxels sets the grid of --method froxel; with --method march it is not used"),
            std::string::npos)
      << unused.err;
}

// --method froxel: every light in the grid, named in the table, and the last frame against the
// path-traced reference. Measured (2026-12) with 256 slices at 16 spp: mean error -0.25 %,
// relative RMSE 2.2 % (at 64 spp +0.08 % and 1.6 %: the rest is the reference's noise; the
// march: -1.6 %, 12 %, its spot apex under-sampled). Held within 1.5 % and 4 %.
TEST_F(Cli, RealtimeFroxelFogMatchesTheReference) {
  const fs::path scene = write("rt.json", kSmallRealtimeScene);
  const RunResult r = run("realtime " + scene.string() + " --method froxel --froxels 64x48x256 --frames 3 "
                          "--reference-spp 16 --compare-reference -o " + (dir_ / "froxel.png").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("light 0 (spot, froxel)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("per light: 0 froxel"), std::string::npos) << r.out;
  double mean_error = 0.0, relative_rmse = 0.0;
  const size_t at = r.out.find("mean error ");
  ASSERT_NE(at, std::string::npos) << r.out;
  ASSERT_EQ(std::sscanf(r.out.c_str() + at, "mean error %lf %%, relative RMSE %lf %%", &mean_error, &relative_rmse), 2)
      << r.out;
  std::printf("froxel against the reference: mean error %.2f %%, relative RMSE %.2f %%\n", mean_error, relative_rmse);
  EXPECT_LT(std::abs(mean_error), 1.5);
  EXPECT_LT(relative_rmse, 4.0);
}

// Area lights and the environment are shaded through stand-ins (realtime/light_stand_ins.h),
// each named in a note and in the table; the lights shaded as they are say nothing.
TEST_F(Cli, RealtimeNamesTheLightsItShadesThroughStandIns) {
  const RunResult r = run("realtime lights-showcase --res 64x36 --frames 1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;
  for (const char* name : {"light 1 (sphere) is shaded in real time as a point light",
                           "light 3 (quad) is shaded in real time as a point light",
                           "light 5 (environment) is shaded in real time as 16 suns"})
    EXPECT_NE(r.err.find(std::string("note: ") + name), std::string::npos) << name << r.err;
  for (const char* name : {"light 0 (", "light 2 (", "light 4 ("})
    EXPECT_EQ(r.err.find(std::string("note: ") + name), std::string::npos) << name << r.err;
  EXPECT_NE(r.out.find("light 1 (sphere, march as point)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("light 5 (environment, march as 16 suns)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("light 2 (point, march)"), std::string::npos) << r.out;
}

// The stand-ins against the path tracer's single-scattering reference, in fog over a floor.
// Measured (2026-12, 128x96, 3 frames, 64 spp per light):
//   quad, sphere and disk lights: mean error -0.29 %, relative RMSE 6.6 % (the point's near
//     field and hard shadows; with a slightly denser fog, 64 and 1024 spp gave -0.56 % and
//     -0.51 %, 6.5 % and 6.4 %: the reference's noise is a small part);
//   a constant sky as 16 suns: mean error -0.76 %, relative RMSE 5.6 % (the suns' banded
//     shadows; 1024 spp took the RMSE from 6.0 to 5.0 % on the denser fog).
// Held to 1.5 % in the mean and 9 % relative RMSE.
TEST_F(Cli, RealtimeStandInsMatchTheReference) {
  const char* floor_and_fog = R"(
  "materials": {"grey": {"type": "diffuse", "reflectance": 0.5}},
  "media": {"fog": {"sigma_s": 0.12, "sigma_a": 0.015}},
  "volumes": [{"type": "box", "min": [-5, 0, -5], "max": [5, 3.5, 5], "medium": "fog"}],)";
  const std::string area = std::string(R"({"camera": {"position": [0, 1.0, 5], "look_at": [0, 0.3, 0]},)") +
                           floor_and_fog + R"(
  "shapes": [{"type": "rectangle", "corner": [-5, 0, -5], "edge1": [0, 0, 10], "edge2": [10, 0, 0], "material": "grey"},
             {"type": "sphere", "center": [0.3, 0.5, 0.5], "radius": 0.5, "material": "grey"}],
  "lights": [{"type": "quad", "corner": [-2.4, 3, -0.4], "edge1": [0.8, 0, 0], "edge2": [0, 0, 0.8], "radiance": 20},
             {"type": "sphere", "center": [1.8, 2.2, -1], "radius": 0.2, "radiance": 40},
             {"type": "disk", "center": [0, 3.2, 1.5], "normal": [0, -1, 0], "radius": 0.3, "radiance": 15}]})";
  const std::string sky = std::string(R"({"camera": {"position": [0, 1.5, 6], "look_at": [0, 1, 0]},)") +
                          floor_and_fog + R"(
  "shapes": [{"type": "rectangle", "corner": [-5, 0, -5], "edge1": [0, 0, 10], "edge2": [10, 0, 0], "material": "grey"},
             {"type": "box", "min": [-0.6, 0, -0.6], "max": [0.6, 1.6, 0.6], "material": "grey"}],
  "lights": [{"type": "environment", "radiance": [0.5, 0.7, 1.0]}]})";
  for (const auto& [name, text] : {std::pair{"area", area}, std::pair{"sky", sky}}) {
    const fs::path scene = write(std::string(name) + ".json", text);
    const RunResult r = run("realtime " + scene.string() + " --res 128x96 --frames 3 -q --reference-spp 64 "
                            "--compare-reference --reference-per-light -o " + (dir_ / (std::string(name) + ".png")).string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    double mean_error = 0.0, relative_rmse = 0.0;
    const size_t at = r.out.find("mean error ");
    ASSERT_NE(at, std::string::npos) << r.out;
    ASSERT_EQ(std::sscanf(r.out.c_str() + at, "mean error %lf %%, relative RMSE %lf %%", &mean_error, &relative_rmse), 2)
        << r.out;
    std::printf("%s stand-ins against the reference: mean error %.2f %%, relative RMSE %.2f %%\n", name, mean_error,
                relative_rmse);
    EXPECT_LT(std::abs(mean_error), 1.5) << name;
    EXPECT_LT(relative_rmse, 9.0) << name;
  }
}

// The artefact "thin occluders": scenes/fence.json, a spot shining through 25 slats 3 cm wide
// 8 cm apart into fog, seen from the side. Measured (2026-12, 320x180, 8 still frames): march
// mean error -0.26 %, relative RMSE 2.2 % against 256 spp (-0.34 %, 3.3 % against 32 spp, the
// run here), frame-to-frame change 0.37 %; froxel -0.36 %, 2.4 %, 1.6 %. Held to 1.5 % in the
// mean, 5 % relative RMSE and 1 % frame-to-frame change.
TEST_F(Cli, RealtimeFenceNeitherLeaksNorFlickers) {
  const std::string scene = std::string(CALIGO_SOURCE_DIR) + "/scenes/fence.json";
  const RunResult r = run("realtime " + scene + " --res 320x180 --frames 8 -q --reference-spp 32 --compare-reference -o " +
                          (dir_ / "fence.png").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  double mean_error = 0.0, relative_rmse = 0.0, change = 0.0;
  const size_t at = r.out.find("mean error "), ch = r.out.find("frame-to-frame change: ");
  ASSERT_NE(at, std::string::npos) << r.out;
  ASSERT_NE(ch, std::string::npos) << r.out;
  ASSERT_EQ(std::sscanf(r.out.c_str() + at, "mean error %lf %%, relative RMSE %lf %%", &mean_error, &relative_rmse), 2)
      << r.out;
  ASSERT_EQ(std::sscanf(r.out.c_str() + ch, "frame-to-frame change: %lf %%", &change), 1) << r.out;
  std::printf("fence: mean error %.2f %%, relative RMSE %.2f %%, frame-to-frame change %.2f %%\n", mean_error,
              relative_rmse, change);
  EXPECT_LT(std::abs(mean_error), 1.5);
  EXPECT_LT(relative_rmse, 5.0);
  EXPECT_LT(change, 1.0);
}

// The artefact matrix's interior wall: a closed room of 12 cm walls with one window, the sun
// outside, fog inside and out (scenes/room.json). Light leaking through a wall, or spread
// from the beam by the low-resolution passes, lands where the reference is dark (75 % of the
// pixels: the room's shadowed fog and walls); the real-time frame puts 0.70 % of its light
// there (0.14 % of it with no gather: the rest is the gather's blur of the beam's edges). A
// wall letting the sun through would light the room's fog: most of the frame's light.
TEST_F(Cli, RealtimeInteriorWallDoesNotLeakTheSun) {
  const std::string scene = std::string(CALIGO_SOURCE_DIR) + "/scenes/room.json";
  const RunResult r = run("realtime " + scene + " --res 320x180 --frames 8 -q --reference-spp 32 --compare-reference -o " +
                          (dir_ / "room.png").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  double mean_error = 0.0, relative_rmse = 0.0, change = 0.0, dark_pixels = 0.0, dark_share = 0.0;
  const size_t at = r.out.find("mean error "), ch = r.out.find("frame-to-frame change: ");
  const size_t dk = r.out.find("where the reference is dark");
  ASSERT_TRUE(at != std::string::npos && ch != std::string::npos && dk != std::string::npos) << r.out;
  ASSERT_EQ(std::sscanf(r.out.c_str() + at, "mean error %lf %%, relative RMSE %lf %%", &mean_error, &relative_rmse), 2)
      << r.out;
  ASSERT_EQ(std::sscanf(r.out.c_str() + ch, "frame-to-frame change: %lf %%", &change), 1) << r.out;
  ASSERT_EQ(std::sscanf(r.out.c_str() + dk, "where the reference is dark (below 1 %% of its mean: %lf %% of the "
                                            "pixels): %lf %%",
                        &dark_pixels, &dark_share),
            2)
      << r.out;
  std::printf("room: mean error %.2f %%, relative RMSE %.2f %%, change %.2f %%, %.3f %% of the light in the "
              "reference's dark %.1f %% of the pixels\n",
              mean_error, relative_rmse, change, dark_share, dark_pixels);
  EXPECT_GT(dark_pixels, 50.0);
  EXPECT_LT(dark_share, 1.0);
  EXPECT_LT(std::abs(mean_error), 1.0);
  EXPECT_LT(relative_rmse, 3.0);
  EXPECT_LT(change, 1.5);
}

// Height fog (scenes/height-fog.json: dense below 0.3 m, thinning over 0.8 m above, a low sun
// and a spot) in both real-time methods against the path tracer, whose tracking uses the
// field's per-interval majorant; the passes take its optical depths in closed form. Measured
// at 256x144 against 16 spp: march +0.28 % mean, relative RMSE 7.2 % (much of it the
// reference's noise; the rest the gather's 15 taps smearing the steep band of sun-lit fog at
// the horizon), froxel -0.24 %, 3.9 %.
TEST_F(Cli, RealtimeHeightFogMatchesTheReference) {
  const std::string scene = std::string(CALIGO_SOURCE_DIR) + "/scenes/height-fog.json";
  for (const char* method : {"march", "froxel"}) {
    const RunResult r = run("realtime " + scene + " --method " + method +
                            " --res 256x144 --frames 8 -q --reference-spp 16 --compare-reference -o " +
                            (dir_ / "height-fog.png").string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    double mean_error = 0.0, relative_rmse = 0.0;
    const size_t at = r.out.find("mean error ");
    ASSERT_NE(at, std::string::npos) << r.out;
    ASSERT_EQ(std::sscanf(r.out.c_str() + at, "mean error %lf %%, relative RMSE %lf %%", &mean_error, &relative_rmse),
              2)
        << r.out;
    std::printf("height fog, %s: mean error %.2f %%, relative RMSE %.2f %%\n", method, mean_error, relative_rmse);
    EXPECT_LT(std::abs(mean_error), 1.0) << method;
    EXPECT_LT(relative_rmse, std::string_view(method) == "march" ? 9.0 : 5.5) << method;
  }
}

// The Wyman & Ramsey hybrid on its built-in scene: every occluder (the ground box, the
// sphere) is closed, so the point light really takes the hybrid, not a fallback.
TEST_F(Cli, RealtimeRunsTheHybridMethodOnAWymanScene) {
  const fs::path out = dir_ / "hybrid.png";
  const RunResult r = run("realtime wyman-20k --method hybrid --res 128x128 --frames 1 -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("light 0 (point, hybrid)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("per light: 0 hybrid"), std::string::npos) << r.out;
  EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;
  EXPECT_GT(fs::file_size(out), 100u);
}

// A spot in forward-scattering fog: --method textured takes it by Hoffman & Preetham's model
// (auto); forced to the isotropic airlight it is left to the march, with a note saying why.
TEST_F(Cli, RealtimeTexturedSpotInAnisotropicFogFollowsTheSpotModel) {
  const fs::path scene = write("hg-spot.json", R"({
    "camera": {"position": [0, 2, 4.5], "look_at": [0, 1, 0], "resolution": [48, 48]},
    "shapes": [{"type": "box", "min": [-5, -0.1, -5], "max": [5, 0, 5], "material": "grey"}],
    "materials": {"grey": {"type": "diffuse", "reflectance": 0.5}},
    "lights": [{"type": "spot", "position": [0.3, 3.8, -0.2], "look_at": [0, 0, 0], "inner_angle": 18,
                "outer_angle": 26, "intensity": 40}],
    "media": {"fog": {"sigma_s": 0.25, "sigma_a": 0.03, "phase": {"type": "hg", "g": 0.5}}},
    "volumes": [{"type": "box", "min": [-5, 0, -5], "max": [5, 5, 5], "medium": "fog"}]})");
  const RunResult hp = run("realtime " + scene.string() + " --method textured --frames 1");
  ASSERT_EQ(hp.exit_code, 0) << hp.err;
  EXPECT_NE(hp.out.find("per light: 0 textured"), std::string::npos) << hp.out;
  const RunResult air = run("realtime " + scene.string() + " --method textured --spot-model airlight --frames 1");
  ASSERT_EQ(air.exit_code, 0) << air.err;
  EXPECT_NE(air.out.find("per light: 0 march"), std::string::npos) << air.out;
  EXPECT_NE(air.err.find("anisotropic phase"), std::string::npos) << air.err;
}

TEST_F(Cli, RealtimeReportsBrokenGoboAndIesFilesWithTheirJsonPath) {
  write("broken.ies", "IESNA:LM-63-2002\nTILT=NONE\n1 1000 1 3 1 1 2 0 0 0\n1 1 100\n0 45\n");
  write("not-an-image.jpg", "this is not a PNG");
  const std::string base = R"({"camera": {"position": [0, 1, 5], "look_at": [0, 1, 0]}, "lights": [)";
  const fs::path ies = write("ies.json", base + R"({"type": "point", "position": [0, 2, 0], "intensity": 1,
                                                   "ies": {"file": "broken.ies"}}]})");
  const RunResult r1 = run("realtime " + ies.string() + " --frames 1");
  EXPECT_EQ(r1.exit_code, 2);
  EXPECT_NE(r1.err.find("/lights/0/ies/file"), std::string::npos) << r1.err;
  const fs::path gobo = write("gobo.json", base + R"({"type": "spot", "position": [0, 2, 0], "look_at": [0, 0, 0],
      "inner_angle": 10, "outer_angle": 20, "intensity": 1, "gobo": {"file": "not-an-image.jpg"}}]})");
  const RunResult r2 = run("render " + gobo.string() + " --spp 1");
  EXPECT_EQ(r2.exit_code, 2);
  EXPECT_NE(r2.err.find("/lights/0/gobo/file"), std::string::npos) << r2.err;
  EXPECT_TRUE(outputs().empty());
}

TEST_F(Cli, RealtimeReferencePerLight) {
  std::string two_lights = kSmallRealtimeScene;
  const std::string spot = R"("lights": [)";
  two_lights.replace(two_lights.find(spot), spot.size(),
                     R"("lights": [{"type": "point", "position": [1, 2, 1], "intensity": 3}, )");
  const fs::path scene = write("rt2.json", two_lights);
  const RunResult r = run("realtime " + scene.string() +
                          " --frames 1 -q --reference-spp 64 --reference-per-light --compare-reference -o " +
                          (dir_ / "last.png").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("64 spp per light"), std::string::npos) << r.out;

  std::string glowing = two_lights;
  const std::string grey = R"({"type": "diffuse", "reflectance": 0.5})";
  glowing.replace(glowing.find(grey), grey.size(), R"({"type": "diffuse", "reflectance": 0.5, "emission": 1})");
  const fs::path emissive = write("rt3.json", glowing);
  const RunResult e = run("realtime " + emissive.string() + " --frames 1 --reference-per-light --compare-reference");
  EXPECT_EQ(e.exit_code, 2);
  EXPECT_NE(e.err.find("--reference-per-light"), std::string::npos) << e.err;
}

// Files in the test directory whose names contain `part` (temporary files included).
int count_files_containing(const fs::path& dir, const std::string& part) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir)) n += e.path().filename().string().find(part) != std::string::npos;
  return n;
}

TEST_F(Cli, GeneratesACloudAndDescribesIt) {
  const fs::path vdb = dir_ / "cloud.vdb";
  const RunResult g = run("generate cloud -o " + vdb.string() + " --res 32 --seed 3");
  ASSERT_EQ(g.exit_code, 0) << g.err;
  ASSERT_TRUE(fs::exists(vdb));
  EXPECT_EQ(count_files_containing(dir_, "tmp"), 0);
  // The generator's summary and `info` agree on the active voxel count.
  const size_t at = g.out.find("density");
  ASSERT_NE(at, std::string::npos) << g.out;
  const std::string active = g.out.substr(at + 7, g.out.find("active", at) - at - 7);
  const std::string count = active.substr(active.find_first_not_of(' '), active.find_last_not_of(' ') -
                                                                              active.find_first_not_of(' ') + 1);
  EXPECT_GT(std::stoll(count), 1000) << g.out;
  const RunResult i = run("info " + vdb.string());
  ASSERT_EQ(i.exit_code, 0) << i.err;
  EXPECT_NE(i.out.find("OpenVDB"), std::string::npos) << i.out;
  EXPECT_NE(i.out.find("density"), std::string::npos) << i.out;
  EXPECT_NE(i.out.find(" " + count + " "), std::string::npos) << i.out << "\nexpected " << count;

  const fs::path nvdb = dir_ / "fire.nvdb";
  ASSERT_EQ(run("generate fire -q -o " + nvdb.string() + " --res 16").exit_code, 0);
  const RunResult n = run("info " + nvdb.string());
  ASSERT_EQ(n.exit_code, 0) << n.err;
  EXPECT_NE(n.out.find("NanoVDB"), std::string::npos) << n.out;
  EXPECT_NE(n.out.find("temperature"), std::string::npos) << n.out;
  EXPECT_NE(n.out.find("flame"), std::string::npos) << n.out;
}

TEST_F(Cli, GridCommandsRejectBadInputAndWriteNothing) {
  const RunResult missing = run("info " + (dir_ / "missing.vdb").string());
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("missing.vdb"), std::string::npos) << missing.err;
  EXPECT_TRUE(missing.out.empty()) << missing.out;

  const fs::path corrupt = write("corrupt.vdb", "this is not a grid file, only words");
  const RunResult c = run("info " + corrupt.string());
  EXPECT_EQ(c.exit_code, 2);
  EXPECT_NE(c.err.find("corrupt.vdb"), std::string::npos) << c.err;
  EXPECT_EQ(std::count(c.err.begin(), c.err.end(), '\n'), 1) << c.err;  // one line

  for (const std::string args : {"generate cloud --res 7 -o ", "generate cloud --res 5000 -o ",
                                 "generate cloud --res many -o ", "generate tornado -o "}) {
    const RunResult r = run(args + (dir_ / "out.vdb").string());
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_FALSE(r.err.empty()) << args;
  }
  const RunResult ext = run("generate smoke -o " + (dir_ / "out.exr").string());
  EXPECT_EQ(ext.exit_code, 2);
  EXPECT_NE(ext.err.find("out.exr"), std::string::npos) << ext.err;
  EXPECT_EQ(count_files_containing(dir_, "out.vdb") + count_files_containing(dir_, "out.exr"), 0);
}

// Grid and mesh volumes in a scene: a bad file stops `render` with a one-line error naming the
// volume's JSON pointer and the file, exit 2, and nothing written.
TEST_F(Cli, BadVolumeFilesInAScene) {
  const auto scene_with_volume = [&](const std::string& volume) {
    return write("vol.json", R"({"camera": {"position": [0, 1, 6], "look_at": [0, 1, 0], "resolution": [8, 8]},
      "media": {"m": {"sigma_s": 1, "blackbody": {}}, "plain": {"sigma_s": 1}},
      "volumes": [)" + volume + "]}");
  };
  write("junk.vdb", "OpenVDB? no: just some words in a file");
  // Half of a real grid file: truncated.
  ASSERT_EQ(run("generate cloud -q -o " + (dir_ / "whole.vdb").string() + " --res 16").exit_code, 0);
  {
    std::ifstream in(dir_ / "whole.vdb", std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream(dir_ / "half.vdb", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  }
  write("open.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\n");
  struct Case {
    std::string volume, expect1, expect2;
  };
  const std::vector<Case> cases = {
      {R"({"type": "vdb", "file": "missing.vdb", "medium": "plain"})", "/volumes/0/file", "missing.vdb"},
      {R"({"type": "vdb", "file": "junk.vdb", "medium": "plain"})", "/volumes/0/file", "junk.vdb"},
      {R"({"type": "vdb", "file": "half.vdb", "medium": "plain"})", "/volumes/0/file", "half.vdb"},
      {R"({"type": "vdb", "file": "whole.vdb", "grids": {"density": "smoke"}, "medium": "plain"})",
       "/volumes/0", "smoke"},
      {R"({"type": "vdb", "file": "whole.vdb", "medium": "m"})", "/volumes/0", "temperature"},
      {R"({"type": "dense", "file": "junk.vdb", "dimensions": [4, 4, 4], "voxel_size": 0.1, "medium": "plain"})",
       "/volumes/0/file", "junk.vdb"},
      {R"({"type": "dense", "file": "junk.vdb", "dimensions": [100000, 4, 4], "voxel_size": 0.1, "medium": "plain"})",
       "/volumes/0/dimensions", ""},
      {R"({"type": "mesh", "file": "open.obj", "medium": "plain"})", "/volumes/0", "cannot bound a volume"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.volume);
    const fs::path scene = scene_with_volume(c.volume);
    const RunResult r = run("render " + scene.string() + " -q -o " + (dir_ / "out.exr").string());
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("vol.json"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(c.expect1), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(c.expect2), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "out.exr"));
    EXPECT_FALSE(fs::exists(dir_ / "out.png"));
  }
  // The same scene with a good grid renders.
  const fs::path good = scene_with_volume(R"({"type": "vdb", "file": "whole.vdb", "medium": "plain"})");
  const RunResult ok = run("render " + good.string() + " -q --spp 1 -o " + (dir_ / "out.exr").string());
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_TRUE(fs::exists(dir_ / "out.exr"));
}

namespace {

// PNG width and height from the IHDR chunk (big-endian at bytes 16 and 20).
std::pair<uint32_t, uint32_t> png_size(const fs::path& path) {
  const std::string bytes = slurp(path);
  if (bytes.size() < 24 || bytes.compare(1, 3, "PNG") != 0) return {0, 0};
  const auto be32 = [&bytes](size_t at) {
    uint32_t v = 0;
    for (size_t i = 0; i < 4; ++i) v = (v << 8) | uint8_t(bytes[at + i]);
    return v;
  };
  return {be32(16), be32(20)};
}

}  // namespace

TEST_F(Cli, BenchTableWymanWritesTheTableAndAStrip) {
  const fs::path out = dir_ / "table";
  const RunResult r =
      run("bench-table wyman --res 64 --scenes wyman-20k --frames 1 --reference-spp 4 -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* want : {"| wyman-20k | 20,480 |", "none @64²", "brute 150 @64²", "hybrid 50 @16²",
                           "textured ≤150 @16²", "march @16²", "brute 25", "brute 2000", "textured 2000",
                           "spot ref. noise", "speed-up (frame)"})
    EXPECT_NE(r.out.find(want), std::string::npos) << want << "\n" << r.out;
  const std::string md = slurp(out / "table.md");
  EXPECT_NE(md.find("| wyman-20k | 20,480 |"), std::string::npos) << md;
  // The step errors (deterministic: the same pipeline against 2000 steps, no reference noise) of
  // the 64² row: columns none, brute 150, hybrid 50, textured, march, brute 25, 50, 100, 300, 600
  // (then textured 2000 and brute 2000, 0 by construction).
  // Measured (2026-12): 1.43, 0.033, 0.007, 0.136, 3.40, 0.182, 0.103, 0.050, 0.017, 0.009 %.
  // What the paper claims of them: shadows matter (none is far off), the hybrid's closed form
  // beats brute force's 150 steps, and brute force converges with its steps.
  const size_t table = md.find("Step error");
  ASSERT_NE(table, std::string::npos) << md;
  const size_t row = md.find("| wyman-20k | 64² |", table);
  ASSERT_NE(row, std::string::npos) << md;
  std::vector<double> step;
  std::istringstream cells(md.substr(row, md.find('\n', row) - row));
  for (std::string cell; std::getline(cells, cell, '|');)
    if (cell.find('%') != std::string::npos) step.push_back(std::stod(cell));
  ASSERT_EQ(step.size(), 12u) << md;
  EXPECT_GT(step[0], 1.0);                // none
  EXPECT_LT(step[2], step[1]);            // hybrid 50 below brute 150
  EXPECT_GT(step[5], step[1]);            // brute 25 above brute 150
  EXPECT_GT(step[1], step[9]);            // brute 150 above brute 600
  // Two rows (scales 1 and 4) of seven 64-pixel panels (none, brute, hybrid, textured on the
  // -spot twin, march, reference, spot reference), 4-pixel gaps.
  const auto [w, h] = png_size(out / "wyman-20k.png");
  EXPECT_EQ(w, 7u * 64u + 6u * 4u);
  EXPECT_EQ(h, 2u * 64u + 4u);
}

TEST_F(Cli, BenchTableRejectsBadOptions) {
  struct Case {
    std::string args, expect, where = "command line";
  };
  const std::vector<Case> cases = {
      {"bench-table nope", "wyman"},
      {"bench-table wyman --scales 1,x", "--scales"},
      {"bench-table wyman --scales 0", "--scales"},
      {"bench-table wyman --res 0", "--res"},
      {"bench-table wyman --frames 0", "--frames"},
      {"bench-table wyman --reference-spp -1", "--reference-spp"},
      {"bench-table wyman --scenes wyman-20k,no-such-scene", "built-in", "no-such-scene"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.args);
    const RunResult r = run(c.args + " -o " + (dir_ / "out").string());
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(c.expect), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(c.where), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "out" / "table.md"));
  }
}

// Process start-up: OpenImageIO (~260 shared libraries, ~100 MB), OpenVDB and assimp are
// plugins (caligo_oiio.so, caligo_vdb.so, caligo_assimp.so) loaded only by runs that use them.
// The dynamic loader's own log (LD_DEBUG=files) lists every object a run maps, at start-up
// or by dlopen: the cause of slow start-up is checked, not a noisy wall time.
namespace {

const char* const kHeavyLibraries[] = {"libOpenImageIO", "libopenvdb", "libassimp",
                                       "caligo_oiio.so", "caligo_vdb.so", "caligo_assimp.so"};

// The file names of the objects the dynamic loader mapped, from LD_DEBUG=files lines such as
// "  1234:	file=libtbb.so.12 [0];  needed by ..." (paths reduced to their last component).
std::vector<std::string> loaded_objects(const std::string& ld_debug_log) {
  std::vector<std::string> names;
  std::istringstream lines(ld_debug_log);
  for (std::string line; std::getline(lines, line);) {
    const size_t at = line.find("file=");
    if (at == std::string::npos) continue;
    const std::string file = line.substr(at + 5, line.find_first_of(" \t", at + 5) - at - 5);
    names.push_back(fs::path(file).filename().string());
  }
  return names;
}

bool any_named(const std::vector<std::string>& names, const std::string& part) {
  return std::any_of(names.begin(), names.end(),
                     [&](const std::string& n) { return n.find(part) != std::string::npos; });
}

}  // namespace

TEST_F(Cli, HeavyLibrariesAreLoadedOnlyByRunsThatUseThem) {
  for (const std::string& args : {std::string("--help"), "render default --res 16x16 --spp 1 -q -o " +
                                                            (dir_ / "small.exr").string()}) {
    const RunResult r = run_with_env("LD_DEBUG=files", args);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::vector<std::string> loaded = loaded_objects(r.err);
    ASSERT_TRUE(any_named(loaded, "libtbb")) << "no loader log for: " << args;  // the log is there
    for (const char* heavy : kHeavyLibraries) EXPECT_FALSE(any_named(loaded, heavy)) << heavy << " in: " << args;
  }
  EXPECT_TRUE(fs::exists(dir_ / "small.png"));  // the PNG preview needs no OpenImageIO

  // The same log sees the plugins when a run needs them.
  const RunResult vdb = run_with_env("LD_DEBUG=files", "generate cloud --res 16 -q -o " + (dir_ / "c.vdb").string());
  ASSERT_EQ(vdb.exit_code, 0) << vdb.err;
  const std::vector<std::string> with_vdb = loaded_objects(vdb.err);
  EXPECT_TRUE(any_named(with_vdb, "caligo_vdb.so"));
  EXPECT_TRUE(any_named(with_vdb, "libopenvdb"));
  EXPECT_FALSE(any_named(with_vdb, "libOpenImageIO"));
}

// --- Hostile input (issue 12): limits, and errors that stay one short line, escaped. ---

TEST_F(Cli, HostileScenesGiveShortLocatedErrorsNotCrashes) {
  std::string deep_pointer = "/camera";
  for (int i = 0; i < 63; ++i) deep_pointer += "/0";  // level 65 opens here
  const std::string mesh = R"({"type": "mesh", "file": "FILE", "material": "white"})";
  const auto mesh_scene = [&](const std::string& file) {
    return scene_with("", "", std::string(mesh).replace(mesh.find("FILE"), 4, file));
  };
  const std::vector<BadCase> cases = {
      // Used to recurse 100,000 deep describing the value (SIGSEGV, exit 139).
      {"deep", R"({"camera": )" + std::string(100000, '[') + std::string(100000, ']') + "}",
       deep_pointer + ": JSON nested more than 64 levels deep"},
      // Used to print the key twice in full: a 2 MB line.
      {"megabyte_key", scene_with("\"fov\"", "\"" + std::string(1 << 20, 'k') + "\": 1, \"fov\""),
       "... (1048576 bytes)\" in the camera"},
      {"huge_index", mesh_scene("huge_index.obj"),
       "huge_index.obj: line 4: a face refers to vertex 100000000000000000000, but the file has 3 vertices"},
      {"short_face", mesh_scene("short_face.obj"), "short_face.obj: line 5: a face has 2 vertices"},
      {"zero_normal", mesh_scene("zero_normal.obj"),
       "zero_normal.obj: line 5: a face uses normal 1, which has zero"},
  };
  write("huge_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 100000000000000000000\n");
  write("short_face.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2\n");
  write("zero_normal.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 0\nf 1//1 2//1 3//1\n");
  for (const BadCase& c : cases) {
    const fs::path scene = write(std::string(c.name) + ".json", c.scene);
    const RunResult r = run("render " + scene.string() + " -q -o " + (dir_ / "out.exr").string());
    EXPECT_EQ(r.exit_code, 2) << c.name << ": " << r.err.substr(0, 500);
    EXPECT_EQ(r.err.rfind("caligo: error: " + scene.string(), 0), 0u)
        << c.name << ": " << r.err.substr(0, 500);
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << c.name << ": " << r.err.substr(0, 500);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << c.name;
    EXPECT_LT(r.err.size(), 400u) << c.name << ": " << r.err.substr(0, 500);
    EXPECT_TRUE(outputs().empty()) << c.name;
  }
}

TEST_F(Cli, ControlCharactersInFileNamesAndArgumentsAreEscaped) {
  // Single quotes carry the newline and the escape sequence through the shell.
  const fs::path scene = write("bad\nname\x1b[1m.json", scene_with("\"spp\": 1", "\"spp\": 0"));
  const RunResult r = run("render '" + scene.string() + "' -q -o " + (dir_ / "out.exr").string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.err.rfind("caligo: error: " + dir_.string() + "/bad\\nname\\x1b[1m.json: /render/spp", 0), 0u)
      << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.find('\x1b'), std::string::npos) << r.err;
  const RunResult command = run("'ren\nder'");
  EXPECT_EQ(command.exit_code, 2);
  EXPECT_EQ(command.err.rfind("caligo: error: unknown command \"ren\\nder\"", 0), 0u) << command.err;
}

TEST_F(Cli, DeeplyNestedMeshFilesAreInputErrorsNotCrashes) {
  // Both used to overflow the stack in the parsing library (SIGSEGV, exit 139).
  const int n = 20000;
  write("deep.gltf", R"({"asset": {"version": "2.0"}, "extras": )" + std::string(n, '[') + std::string(n, ']') + "}");
  std::string nodes;
  for (int i = 0; i < n; ++i) nodes += "<node>";
  for (int i = 0; i < n; ++i) nodes += "</node>";
  write("deep.dae", "<COLLADA><library_visual_scenes><visual_scene>" + nodes +
                        "</visual_scene></library_visual_scenes></COLLADA>");
  for (const std::string file : {"deep.gltf", "deep.dae"}) {
    const std::string shape = R"({"type": "mesh", "file": ")" + file + R"(", "material": "white"})";
    const fs::path scene = write(file + ".json", scene_with("", "", shape));
    const RunResult r = run("render " + scene.string() + " -q -o " + (dir_ / "out.exr").string());
    EXPECT_EQ(r.exit_code, 2) << file << ": " << r.err.substr(0, 500);
    EXPECT_NE(r.err.find(file + ": line 1: "), std::string::npos) << r.err.substr(0, 500);
    EXPECT_NE(r.err.find("levels deep"), std::string::npos) << r.err.substr(0, 500);
    EXPECT_TRUE(outputs().empty()) << file;
  }
}
