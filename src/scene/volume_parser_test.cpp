// Grid, dense and mesh volumes in scene files, the artist's medium form and emission
// channels: what parses, and located errors for what does not.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <unistd.h>

#include "scene/scene_parser.h"
#include "volumes/mesh_volume.h"
#include "volumes/volume_context.h"

namespace caligo {
namespace {

namespace fs = std::filesystem;

std::string temp_dir() {
  const fs::path dir = fs::temp_directory_path() / ("caligo_volume_parser_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir.string();
}

void write_text(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

// A unit cube as an OBJ, optionally missing its top face (then it cannot bound a volume).
std::string cube_obj(bool closed) {
  std::string obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n";
  obj += "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 4 8 7\nf 4 7 3\n";
  if (closed) obj += "f 1 5 8\nf 1 8 4\n";
  return obj;
}

SceneDesc parse(const std::string& media, const std::string& volumes, const std::string& base_dir = "") {
  return parse_scene_text(R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]}, "media": )" + media +
                              R"(, "volumes": )" + volumes + "}",
                          "vol.json", base_dir);
}

std::string error_of(const std::string& media, const std::string& volumes, const std::string& base_dir = "") {
  try {
    parse(media, volumes, base_dir);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(VolumeParser, AlbedoAndExtinctionGiveTheCoefficients) {
  const SceneDesc s = parse(R"({"m": {"albedo": [0.9, 0.5, 0], "extinction": 2}})",
                            R"([{"type": "sphere", "center": [0, 0, 0], "radius": 1, "medium": "m"}])");
  const VolumeShader& m = s.volumes[0].shader;
  EXPECT_FLOAT_EQ(m.sigma_s.r, 1.8f);
  EXPECT_FLOAT_EQ(m.sigma_a.r, 0.2f);
  EXPECT_FLOAT_EQ(m.sigma_s.b, 0.0f);
  EXPECT_FLOAT_EQ(m.sigma_a.b, 2.0f);
  EXPECT_NE(error_of(R"({"m": {"albedo": 0.5, "extinction": 1, "sigma_s": 1}})",
                     R"([{"type": "sphere", "center": [0, 0, 0], "radius": 1, "medium": "m"}])")
                .find("/media/m: give either"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"m": {"albedo": 1.5, "extinction": 1}})",
                     R"([{"type": "sphere", "center": [0, 0, 0], "radius": 1, "medium": "m"}])")
                .find("/media/m/albedo"),
            std::string::npos);
}

// "holdout": the grey holdout extinction sigma_h, beside sigma_a and sigma_s or albedo/extinction;
// it scales with density like them (MediumSample::holdout).
TEST(VolumeParser, HoldoutExtinction) {
  const std::string sphere = R"([{"type": "sphere", "center": [0, 0, 0], "radius": 1, "medium": "m"}])";
  EXPECT_FLOAT_EQ(parse(R"({"m": {"sigma_s": 1}})", sphere).volumes[0].shader.holdout, 0.0f);
  const VolumeShader a = parse(R"({"m": {"sigma_s": 1, "holdout": 2.5}})", sphere).volumes[0].shader;
  EXPECT_FLOAT_EQ(a.holdout, 2.5f);
  EXPECT_EQ(a.sigma_s, RGB(1.0f));
  const SceneDesc b = parse(R"({"m": {"albedo": 0.5, "extinction": 2, "holdout": 4, "density": 0.5}})", sphere);
  EXPECT_FLOAT_EQ(b.volumes[0].shader.holdout, 4.0f);
  VolumeContext context;
  const MediumSample m = shade_volume(b.volumes[0], Vec3(0.0f), context);
  EXPECT_FLOAT_EQ(m.holdout, 2.0f);  // 4 x density 0.5
  EXPECT_EQ(m.sigma_t(), RGB(0.5f + 0.5f + 2.0f));
  EXPECT_NE(error_of(R"({"m": {"holdout": -1}})", sphere).find("/media/m/holdout"), std::string::npos);
  EXPECT_NE(error_of(R"({"m": {"holdout": true}})", sphere).find("/media/m/holdout: expected a number"),
            std::string::npos);
}

TEST(VolumeParser, GeneratedGridVolumeIsABoxOverTheGrid) {
  const SceneDesc s = parse(R"({"fire": {"sigma_a": 1, "blackbody": {"intensity": 1e-5}, "step_scale": 2}})",
                            R"([{"type": "vdb", "generate": {"kind": "fire", "resolution": 16, "seed": 2},
                                 "filter": "nearest", "medium": "fire"}])");
  ASSERT_EQ(s.volumes.size(), 1u);
  const auto& field = std::get<GridDensity>(s.volumes[0].shader.field);
  EXPECT_EQ(field.filter, GridFilter::kNearest);
  EXPECT_TRUE(field.grid->has_temperature());
  EXPECT_FLOAT_EQ(s.volumes[0].shader.step_scale, 2.0f);
  const Bounds3 shape = volume_bounds(s.volumes[0].shape), grid = field.grid->world_bounds();
  EXPECT_NEAR(shape.lo.y, grid.lo.y, 1e-5f);
  EXPECT_NEAR(shape.hi.x, grid.hi.x, 1e-5f);
}

TEST(VolumeParser, EmissionNeedsTheGridChannel) {
  // The cloud has no temperature channel; a sphere has no grid at all.
  EXPECT_NE(error_of(R"({"c": {"sigma_s": 1, "blackbody": {}}})",
                     R"([{"type": "vdb", "generate": {"kind": "cloud", "resolution": 16}, "medium": "c"}])")
                .find("/volumes/0: the medium has blackbody emission but the grid has no temperature"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"c": {"sigma_s": 1, "flame": {"intensity": 2}}})",
                     R"([{"type": "sphere", "center": [0, 0, 0], "radius": 1, "medium": "c"}])")
                .find("needs a grid volume"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"c": {"sigma_s": 1}})",
                     R"([{"type": "vdb", "generate": {"kind": "cloud"}, "filter": "cubic", "medium": "c"}])")
                .find("/volumes/0/filter"),
            std::string::npos);
}

TEST(VolumeParser, MissingAndCorruptGridFilesAreLocated) {
  const std::string dir = temp_dir();
  const std::string e1 = error_of(R"({"c": {"sigma_s": 1}})",
                                  R"([{"type": "vdb", "file": "nowhere.vdb", "medium": "c"}])", dir);
  EXPECT_NE(e1.find("/volumes/0/file"), std::string::npos) << e1;
  EXPECT_NE(e1.find("nowhere.vdb"), std::string::npos) << e1;
  write_text(dir + "/junk.vdb", "this is not a VDB file at all, just text");
  const std::string e2 =
      error_of(R"({"c": {"sigma_s": 1}})", R"([{"type": "vdb", "file": "junk.vdb", "medium": "c"}])", dir);
  EXPECT_NE(e2.find("/volumes/0/file"), std::string::npos) << e2;
  EXPECT_NE(e2.find("junk.vdb"), std::string::npos) << e2;
}

TEST(VolumeParser, DenseGridFromARawFile) {
  const std::string dir = temp_dir();
  std::vector<float> values(4 * 3 * 2, 0.0f);
  values[5] = 0.75f;
  {
    std::ofstream out(dir + "/puff.raw", std::ios::binary);
    out.write(reinterpret_cast<const char*>(values.data()), std::streamsize(values.size() * sizeof(float)));
  }
  const SceneDesc s = parse(R"({"c": {"sigma_s": 1}})",
                            R"([{"type": "dense", "file": "puff.raw", "dimensions": [4, 3, 2], "voxel_size": 0.5,
                                 "medium": "c"}])",
                            dir);
  const auto& field = std::get<GridDensity>(s.volumes[0].shader.field);
  EXPECT_FLOAT_EQ(field.grid->max_density(), 0.75f);
  EXPECT_EQ(field.grid->statistics().active_voxels, 1u);
  // The file holds 24 floats, not 4 x 3 x 3.
  const std::string e = error_of(R"({"c": {"sigma_s": 1}})",
                                 R"([{"type": "dense", "file": "puff.raw", "dimensions": [4, 3, 3],
                                      "voxel_size": 0.5, "medium": "c"}])",
                                 dir);
  EXPECT_NE(e.find("/volumes/0/file"), std::string::npos) << e;
  EXPECT_NE(e.find("puff.raw"), std::string::npos) << e;
  EXPECT_NE(error_of(R"({"c": {"sigma_s": 1}})",
                     R"([{"type": "dense", "file": "puff.raw", "dimensions": [4, 3, 2.5], "voxel_size": 0.5,
                          "medium": "c"}])",
                     dir)
                .find("/volumes/0/dimensions/2: expected a whole number"),
            std::string::npos);
}

TEST(VolumeParser, MeshVolumesMustBeClosed) {
  const std::string dir = temp_dir();
  write_text(dir + "/cube.obj", cube_obj(true));
  write_text(dir + "/open.obj", cube_obj(false));
  const SceneDesc s = parse(R"({"c": {"sigma_s": 1}})",
                            R"([{"type": "mesh", "file": "cube.obj", "medium": "c",
                                 "transform": [{"translate": [0, 0, 2]}]}])",
                            dir);
  const auto& mesh = std::get<MeshVolumeShape>(s.volumes[0].shape);
  EXPECT_NEAR(mesh.mesh->bounds().lo.z, 2.0f, 1e-6f);
  const std::string e =
      error_of(R"({"c": {"sigma_s": 1}})", R"([{"type": "mesh", "file": "open.obj", "medium": "c"}])", dir);
  EXPECT_NE(e.find("vol.json: /volumes/0"), std::string::npos) << e;
  EXPECT_NE(e.find("cannot bound a volume"), std::string::npos) << e;
}

TEST(VolumeParser, AnOpenMeshIsReadByParityWhenAskedWithALocatedWarning) {
  const std::string dir = temp_dir();
  write_text(dir + "/open.obj", cube_obj(false));  // the x = 0 face is missing
  const SceneDesc s = parse(R"({"c": {"sigma_s": 1}})",
                            R"([{"type": "mesh", "file": "open.obj", "medium": "c", "open_edges": "parity"}])", dir);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("vol.json: /volumes/0: the mesh is not closed"), std::string::npos) << s.warnings[0];
  EXPECT_NE(s.warnings[0].find("4 edges"), std::string::npos) << s.warnings[0];
  const MeshVolume& mesh = *std::get<MeshVolumeShape>(s.volumes[0].shape).mesh;
  std::vector<SurfaceHit> hits;
  std::vector<RayRange> inside;
  // Through two faces that are there: the cube's whole depth.
  mesh.intervals(Ray{{0.5f, 0.4f, -3}, {0, 0, 1}, 0, 10}, hits, inside);
  ASSERT_EQ(inside.size(), 1u);
  EXPECT_NEAR(inside[0].t1 - inside[0].t0, 1.0f, 1e-4f);
  // Through the hole: one crossing, dropped, and no medium rather than a half-infinite one.
  inside.clear();
  mesh.intervals(Ray{{-3, 0.4f, 0.6f}, {1, 0, 0}, 0, 10}, hits, inside);
  EXPECT_TRUE(inside.empty());
  // A closed mesh with the option warns of nothing.
  write_text(dir + "/cube.obj", cube_obj(true));
  EXPECT_TRUE(parse(R"({"c": {"sigma_s": 1}})",
                    R"([{"type": "mesh", "file": "cube.obj", "medium": "c", "open_edges": "parity"}])", dir)
                  .warnings.empty());
  EXPECT_NE(error_of(R"({"c": {"sigma_s": 1}})",
                     R"([{"type": "mesh", "file": "cube.obj", "medium": "c", "open_edges": "fill"}])", dir)
                .find("/volumes/0/open_edges"),
            std::string::npos);
}

}  // namespace
}  // namespace caligo
