// Nothing lost, nothing overwritten, through the real binary: no command's output may replace a
// file it reads; every writing command on a full or read-only disk replaces nothing (exit 3);
// damaged checkpoints and changed assets are refused, the checkpoint left in place; an
// interrupted render keeps the earlier finished image; a finished render whose checkpoint does
// not fit keeps its image; lying image headers are refused before they are allocated; seeds
// and non-finite pixels are validated; concurrent writers leave one complete file.
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <variant>

#include "cli_testing.h"
#include "image/exr_io.h"

namespace {

using namespace caligo_cli;

class Outputs : public CliFixture {
 protected:
  // A scene lit by an environment map `map` (a file beside it) and a spot with gobo `gobo`,
  // over a mesh `mesh`: every kind of input a scene reads.
  fs::path scene_with_inputs() {
    const fs::path sky = dir_ / "sky.exr";
    EXPECT_EQ(run("render furnace --res 8x4 --spp 1 -q -o " + sky.string()).exit_code, 0);  // sky.exr, sky.png
    write("tetra.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
    return write("scene.json", R"({
      "camera": {"position": [0, 0.5, 4], "look_at": [0, 0.3, 0], "fov": 40, "resolution": [16, 12]},
      "render": {"spp": 2},
      "materials": {"white": {"type": "diffuse", "reflectance": 0.6}},
      "shapes": [{"type": "mesh", "file": "tetra.obj", "material": "white"}],
      "lights": [{"type": "environment", "map": {"file": "sky.exr"}},
                 {"type": "spot", "position": [0, 3, 0], "look_at": [0, 0, 0], "inner_angle": 20,
                  "outer_angle": 30, "intensity": 5, "gobo": {"file": "sky.png"}}]})");
  }
  // The bytes of a file, for "unchanged" checks.
  static std::string bytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
  // No temporaries or probes of ours in `folder`.
  static int leftovers(const fs::path& folder) {
    int n = 0;
    for (const auto& e : fs::directory_iterator(folder))
      if (e.path().filename().string().find(".tmp-") != std::string::npos ||
          e.path().filename().string().find(".probe-") != std::string::npos)
        ++n;
    return n;
  }
};

TEST_F(Outputs, NoOutputReplacesAnInput) {
  const fs::path scene = scene_with_inputs();
  const std::string sky = bytes(dir_ / "sky.exr"), gobo = bytes(dir_ / "sky.png"), text = bytes(scene);
  fs::create_hard_link(dir_ / "sky.exr", dir_ / "linked.exr");
  fs::create_symlink(dir_ / "tetra.obj", dir_ / "mesh.ckpt");
  const std::string render = "render " + scene.string() + " -q ";
  const auto refused = [&](const std::string& command, const std::string& input) {
    const RunResult r = run(command);
    EXPECT_EQ(r.exit_code, 2) << command << ": " << r.err;
    EXPECT_NE(r.err.find(input), std::string::npos) << command << ": " << r.err;
    EXPECT_NE(r.err.find("reads"), std::string::npos) << command << ": " << r.err;
  };
  refused(render + "-o " + (dir_ / "sky.exr").string(), "sky.exr");           // the environment map
  refused(render + "-o " + (dir_ / "linked.exr").string(), "sky.exr");        // a hard link to it
  refused(render + "-o " + (dir_ / "sky.partial.exr").string() + " --checkpoint " + scene.string(),
          "scene.json");                                                       // the scene as checkpoint
  refused(render + "-o " + (dir_ / "out.exr").string() + " --checkpoint " + (dir_ / "mesh.ckpt").string(),
          "tetra.obj");                                                        // a symlink to the mesh
  refused("realtime " + scene.string() + " --frames 1 -q -o " + (dir_ / "sky.png").string(), "sky.png");  // gobo
  EXPECT_EQ(bytes(dir_ / "sky.exr"), sky);
  EXPECT_EQ(bytes(dir_ / "sky.png"), gobo);
  EXPECT_EQ(bytes(scene), text);
  // A resumed checkpoint may be saved again under its own name, and nothing else may be it.
  const std::string ckpt = (dir_ / "r.ckpt").string();
  ASSERT_EQ(run(render + "-o " + (dir_ / "r.exr").string() + " --checkpoint " + ckpt).exit_code, 0);
  EXPECT_EQ(run(render + "--spp 4 -o " + (dir_ / "r.exr").string() + " --checkpoint " + ckpt + " --resume " + ckpt)
                .exit_code,
            0);
}

TEST_F(Outputs, EveryCommandOnAFullDiskReplacesNothing) {
  if (!mount_tmpfs("full", "size=24k")) GTEST_SKIP() << "cannot mount a tmpfs here (needs root)";
  const fs::path full = dir_ / "full";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"g.vdb", "generate cloud --res 64 -q -o "},
      {"g.nvdb", "generate smoke --res 64 -q -o "},
      {"r.png", "realtime lamp-in-fog --res 480x360 --frames 2 -q -o "},
      {"r.gif", "realtime lamp-in-fog --res 160x120 --frames 6 -q -o "},
  };
  for (const auto& [name, command] : cases) {
    std::ofstream(full / name) << "old";
    const RunResult r = run(command + (full / name).string());
    EXPECT_EQ(r.exit_code, 3) << command << ": " << r.err;
    EXPECT_NE(r.err.find("nothing was replaced"), std::string::npos) << r.err;
    EXPECT_TRUE(slurp(full / name) == "old") << name << " was replaced";
    EXPECT_EQ(leftovers(full), 0) << name;
  }
  // A folder of frames: the frames that fitted are not left half a set.
  const RunResult frames = run("realtime lamp-in-fog --res 160x120 --frames 8 -q -o " + (full / "frames").string());
  EXPECT_EQ(frames.exit_code, 3) << frames.err;
  EXPECT_FALSE(fs::exists(full / "frames")) << "the folder this run made stays only with its frames";
}

TEST_F(Outputs, ReadOnlyFoldersAreRefusedBeforeTheWork) {
  if (!mount_tmpfs("ro", "size=1m")) GTEST_SKIP() << "cannot mount a tmpfs here (needs root)";
  remount_read_only("ro");
  const fs::path ro = dir_ / "ro";
  for (const std::string& command :
       {"generate cloud --res 256 -q -o " + (ro / "g.vdb").string(),
        "realtime lamp-in-fog --frames 200 -q -o " + (ro / "r.gif").string(),
        "realtime lamp-in-fog --frames 200 -q -o " + (ro / "frames").string(),
        "bench-table wyman --res 64 --frames 50 --scenes wyman-20k -o " + (ro / "table").string()}) {
    const auto start = std::chrono::steady_clock::now();
    const RunResult r = run(command);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(r.exit_code, 3) << command << ": " << r.err;
    EXPECT_LT(seconds, 5.0) << command << " worked before failing";
  }
}

TEST_F(Outputs, DamagedCheckpointsAreRefusedAndKept) {
  const std::string ckpt = (dir_ / "c.ckpt").string(), out = " -q -o " + (dir_ / "c.exr").string();
  ASSERT_EQ(run("render lamp-in-fog --res 24x16 --spp 4 --checkpoint " + ckpt + out).exit_code, 0);
  const std::string clean = bytes(ckpt);
  for (size_t at : {size_t(60), clean.size() / 2, clean.size() - 40}) {  // a count, a sum, the last sums
    std::string damaged = clean;
    damaged[at] = char(damaged[at] ^ 0x04);
    std::ofstream(ckpt, std::ios::binary) << damaged;
    const RunResult r = run("render lamp-in-fog --res 24x16 --spp 8 --resume " + ckpt + " --checkpoint " + ckpt + out);
    EXPECT_EQ(r.exit_code, 2) << at << ": " << r.err;
    EXPECT_NE(r.err.find("c.ckpt"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("checksum"), std::string::npos) << r.err;
    EXPECT_EQ(bytes(ckpt), damaged) << "the checkpoint was replaced";
  }
}

TEST_F(Outputs, AChangedAssetRefusesTheResume) {
  const fs::path scene = scene_with_inputs();
  const std::string ckpt = (dir_ / "a.ckpt").string(), out = " -q -o " + (dir_ / "a.exr").string();
  ASSERT_EQ(run("render " + scene.string() + " --checkpoint " + ckpt + out).exit_code, 0);
  write("tetra.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1.5\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  const RunResult r = run("render " + scene.string() + " --spp 4 --resume " + ckpt + out);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("another scene"), std::string::npos) << r.err;
}

TEST_F(Outputs, AnInterruptKeepsTheFinishedImage) {
  const fs::path exr = dir_ / "i.exr";
  ASSERT_EQ(run("render lamp-in-fog --res 48x32 --spp 2 -q -o " + exr.string()).exit_code, 0);
  const std::string finished = bytes(exr);
  const RunResult r =
      run_with_env("timeout --preserve-status -s TERM 1.5", "render lamp-in-fog --res 48x32 --spp 100000 -q -o " +
                                                                exr.string());
  ASSERT_EQ(r.exit_code, 128 + 15) << r.err;
  EXPECT_EQ(bytes(exr), finished);
  EXPECT_TRUE(fs::exists(dir_ / "i.partial.exr") && fs::exists(dir_ / "i.partial.png")) << r.err;
  EXPECT_NE(r.err.find("i.partial.exr"), std::string::npos) << r.err;
}

TEST_F(Outputs, AFinalCheckpointThatDoesNotFitKeepsTheImage) {
  if (!mount_tmpfs("tiny", "size=8k")) GTEST_SKIP() << "cannot mount a tmpfs here (needs root)";
  const std::string ckpt = (dir_ / "tiny" / "f.ckpt").string();
  const RunResult r = run("render lamp-in-fog --res 48x32 --spp 2 --aov all -q --checkpoint " + ckpt + " -o " +
                          (dir_ / "f.exr").string());
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("f.ckpt"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("were written"), std::string::npos) << r.err;
  EXPECT_NO_THROW(caligo::read_exr((dir_ / "f.exr").string()));
  EXPECT_TRUE(fs::exists(dir_ / "f.png"));
  EXPECT_FALSE(fs::exists(ckpt));
}

TEST_F(Outputs, LyingImageHeadersAreRefusedBeforeAllocation) {
  // A PFM whose header claims 16384 x 16384 RGB floats (3 GiB) over 1 KiB of data.
  std::ofstream(dir_ / "huge.pfm", std::ios::binary) << "PF\n16384 16384\n-1.0\n" << std::string(1000, '\0');
  write("env.json", R"({"camera": {"position": [0, 0, 4], "look_at": [0, 0, 0], "resolution": [8, 8]},
                        "lights": [{"type": "environment", "map": {"file": "huge.pfm"}}]})");
  const RunResult r = run("render " + (dir_ / "env.json").string() + " -q -o " + (dir_ / "e.exr").string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("/lights/0/map/file"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("claims 16384x16384"), std::string::npos) << r.err;
}

TEST_F(Outputs, SeedsAndNonFinitePixelsAreChecked) {
  for (const char* seed : {"-1", "18446744073709551616", "9223372036854775808", "7x"}) {
    const RunResult g = run(std::string("generate cloud --res 8 -q --seed ") + seed + " -o " + (dir_ / "s.vdb").string());
    EXPECT_EQ(g.exit_code, 2) << seed << ": " << g.err;
    EXPECT_NE(g.err.find("--seed"), std::string::npos) << g.err;
  }
  EXPECT_FALSE(fs::exists(dir_ / "s.vdb"));
  caligo::Image image(2, 1, {"R", "G", "B"});
  const fs::path clean = dir_ / "clean.exr", bad = dir_ / "nan.exr";
  caligo::write_exr(clean.string(), image);
  image.at(1, 0, 1) = std::numeric_limits<float>::quiet_NaN();
  image.at(0, 0, 2) = std::numeric_limits<float>::infinity();
  caligo::write_exr(bad.string(), image);
  for (const std::string& pair : {bad.string() + " " + clean.string(), clean.string() + " " + bad.string()}) {
    const RunResult r = run("compare " + pair);
    EXPECT_EQ(r.exit_code, 4) << r.err;
    EXPECT_NE(r.err.find("2 NaN or infinite"), std::string::npos) << r.err;
  }
}

TEST_F(Outputs, ConcurrentWritersLeaveOneCompleteFile) {
  const fs::path grid = dir_ / "c.vdb";
  const std::string one = std::string(CALIGO_BINARY) + " generate cloud --res 48 -q --seed ";
  const std::string both = one + "1 -o " + grid.string() + " & " + one + "2 -o " + grid.string() + " & wait";
  ASSERT_EQ(std::system(both.c_str()), 0);
  const RunResult info = run("info " + grid.string());
  EXPECT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("density"), std::string::npos) << info.out;
  EXPECT_EQ(leftovers(dir_), 0);
}

// A frame folder named with a trailing slash is made like any other.
TEST_F(Outputs, AFolderNamedWithATrailingSlashIsMade) {
  const RunResult r = run("realtime lamp-in-fog --res 32x24 --frames 2 -q -o " + (dir_ / "frames").string() + "/");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "frames" / "frame_0001.png"));
}

}  // namespace

// The EXR header records the render as renderers do (software, samples actually rendered,
// seed, scene, time, OpenEXR's camera matrices), and --view picks the PNG's tone curve.
TEST_F(Outputs, TheExrHeaderRecordsTheRenderAndViewPicksThePreviewCurve) {
  const fs::path exr = dir_ / "meta.exr";
  ASSERT_EQ(run("render default --res 24x16 --spp 3 --seed 12345678901 -q -o " + exr.string()).exit_code, 0);
  const caligo::ExrAttributes header = caligo::read_exr_attributes(exr.string());
  const auto text = [&](const char* name) {
    const caligo::ExrValue* v = caligo::find_attribute(header, name);
    return v && std::holds_alternative<std::string>(*v) ? std::get<std::string>(*v) : std::string("(missing)");
  };
  const auto integer = [&](const char* name) {
    const caligo::ExrValue* v = caligo::find_attribute(header, name);
    return v && std::holds_alternative<int>(*v) ? std::get<int>(*v) : -1;
  };
  EXPECT_EQ(text("software").rfind("Caligo ", 0), 0u) << text("software");
  EXPECT_EQ(text("caligo/scene"), "builtin:default");
  EXPECT_EQ(text("caligo/seed"), "12345678901");
  EXPECT_EQ(integer("caligo/samples"), 3);
  EXPECT_EQ(integer("caligo/samplesMax"), 3);
  EXPECT_EQ(text("capDate").size(), 19u);
  const caligo::ExrValue* time = caligo::find_attribute(header, "caligo/renderTime");
  ASSERT_TRUE(time && std::holds_alternative<float>(*time));
  EXPECT_GT(std::get<float>(*time), 0.0f);
  // default's camera looks at its target from its position: worldToCamera puts the target
  // straight ahead (x = y = 0, z = the distance), and worldToNDC at the image's centre.
  const caligo::ExrValue* view = caligo::find_attribute(header, "worldToCamera");
  const caligo::ExrValue* ndc = caligo::find_attribute(header, "worldToNDC");
  ASSERT_TRUE(view && ndc && std::holds_alternative<caligo::Mat4>(*view) && std::holds_alternative<caligo::Mat4>(*ndc));
  const std::string shown = run("scene show default").out;
  const auto vec3_after = [&](const std::string& key) {
    const size_t at = shown.find("[", shown.find("\"" + key + "\"", shown.find("\"camera\"")));
    float v[3];
    EXPECT_EQ(std::sscanf(shown.c_str() + at, "[%f,%f,%f]", &v[0], &v[1], &v[2]), 3) << shown.substr(at, 40);
    return std::array<float, 3>{v[0], v[1], v[2]};
  };
  const auto eye = vec3_after("position"), target = vec3_after("look_at");
  const auto apply = [&](const caligo::Mat4& m, int row) {
    const auto& r = m.m[size_t(row)];
    return r[0] * target[0] + r[1] * target[1] + r[2] * target[2] + r[3];
  };
  const caligo::Mat4& v = std::get<caligo::Mat4>(*view);
  const float distance = std::hypot(target[0] - eye[0], target[1] - eye[1], target[2] - eye[2]);
  EXPECT_NEAR(apply(v, 0), 0.0f, 1e-4f);
  EXPECT_NEAR(apply(v, 1), 0.0f, 1e-4f);
  EXPECT_NEAR(apply(v, 2), distance, 1e-4f);
  const caligo::Mat4& n = std::get<caligo::Mat4>(*ndc);
  EXPECT_NEAR(apply(n, 0) / apply(n, 3), 0.5f, 1e-5f);
  EXPECT_NEAR(apply(n, 1) / apply(n, 3), 0.5f, 1e-5f);
  // The same render's preview with the standard view: a different PNG; a bad view is refused.
  const fs::path standard = dir_ / "standard.exr";
  ASSERT_EQ(run("render default --res 24x16 --spp 3 --seed 12345678901 -q --view standard -o " + standard.string()).exit_code, 0);
  EXPECT_NE(bytes(dir_ / "meta.png"), bytes(dir_ / "standard.png"));
  const RunResult bad = run("render default --res 8x8 --spp 1 --view neon -o " + (dir_ / "bad.exr").string());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--view"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir_ / "bad.exr"));
}

// --preview's port is checked before any work: a bad one is exit 2 naming the option, nothing written.
TEST_F(Outputs, ABadPreviewPortIsRefusedFirst) {
  for (const char* port : {"abc", "70000", "-1", "8080x"}) {
    const RunResult r = run(std::string("render default --res 8x8 --spp 1 --preview ") + port + " -o " +
                            (dir_ / "p.exr").string());
    EXPECT_EQ(r.exit_code, 2) << port << ": " << r.err;
    EXPECT_NE(r.err.find("--preview"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "p.exr"));
  }
}
