// The "opacity" key of materials (docs/scene-format.md): a number, or an image read as data (no
// sRGB decoding) into the material's OpacityMap; OBJ texture coordinates for it; located errors
// for emitters, medium boundaries, values out of range, unreadable images, and shapes that have no
// texture coordinates or are holdouts.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "image/png_io.h"
#include "scene/mesh_loader.h"
#include "scene/scene.h"
#include "scene/scene_parser.h"

namespace caligo {
namespace {

namespace fs = std::filesystem;

class OpacityFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = fs::temp_directory_path() / ("caligo_opacity_parser_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    // 2 x 1: grey 128 (0.502 as data; 0.216 had it been sRGB-decoded), then white.
    write_png((dir / "mask.png").string(), 2, 1, {128, 128, 128, 255, 255, 255});
    std::ofstream(dir / "broken.png") << "not a picture";
    std::ofstream(dir / "card.obj") << "v 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nf 1/1 2/2 3/3\n";
  }
  void TearDown() override { fs::remove_all(dir); }

  SceneDesc parse(const std::string& material, const std::string& shape = R"({"type": "rectangle", "corner": [0, 0, 0], "edge1": [1, 0, 0], "edge2": [0, 1, 0], "material": "m"})") {
    return parse_scene_text(R"({"camera": {"position": [0, 1, 5], "look_at": [0, 1, 0]}, "materials": {"m": )" +
                                material + R"(}, "shapes": [)" + shape + "]}",
                            "t.json", dir.string());
  }
  // The error's JSON pointer and message, from parsing or from building the scene.
  std::pair<std::string, std::string> error(const std::string& material, const std::string& shape = "") {
    try {
      const SceneDesc desc = shape.empty() ? parse(material) : parse(material, shape);
      Scene::build(desc);
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().file, "t.json");
      return {e.where().json_path, e.what()};
    }
    ADD_FAILURE() << "no error for " << material << " " << shape;
    return {};
  }
  fs::path dir;
};

TEST_F(OpacityFiles, ANumberAndAnImageAreRead) {
  EXPECT_FLOAT_EQ(parse(R"({"type": "diffuse", "reflectance": 0.5, "opacity": 0.3})").materials[0].opacity, 0.3f);
  const SceneDesc desc = parse(R"({"type": "dielectric", "opacity": "mask.png"})");
  const Material& m = desc.materials[0];
  ASSERT_TRUE(m.opacity_map);
  EXPECT_TRUE(partly_transparent(m));
  EXPECT_NEAR(m.opacity_map->lookup({0.25f, 0.5f}), 128.0f / 255.0f, 1e-6f);
  EXPECT_NEAR(m.opacity_map->lookup({0.75f, 0.5f}), 1.0f, 1e-6f);
  EXPECT_FALSE(partly_transparent(parse(R"({"type": "diffuse", "reflectance": 0.5})").materials[0]));
  // The image on a rectangle (its own texture coordinates) and on an OBJ with "vt" builds.
  const auto scene = Scene::build(desc);
  EXPECT_TRUE(scene->has_transparent_surfaces());
  Scene::build(parse(R"({"type": "dielectric", "opacity": "mask.png"})", R"({"type": "mesh", "file": "card.obj", "material": "m"})"));
}

TEST_F(OpacityFiles, ObjTextureCoordinatesBecomeTheMeshUvs) {
  const TriangleMesh mesh = load_mesh((dir / "card.obj").string(), {"t.json", "/shapes/0"});
  ASSERT_EQ(mesh.uvs.size(), mesh.positions.size());
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    EXPECT_FLOAT_EQ(mesh.uvs[v].x, mesh.positions[v].x);
    EXPECT_FLOAT_EQ(mesh.uvs[v].y, mesh.positions[v].y);
  }
}

TEST_F(OpacityFiles, BadOpacitiesAreLocatedErrors) {
  const auto expect = [&](std::pair<std::string, std::string> e, const std::string& path, const std::string& words) {
    EXPECT_EQ(e.first, path) << e.second;
    EXPECT_NE(e.second.find(words), std::string::npos) << e.second;
  };
  expect(error(R"({"type": "diffuse", "reflectance": 0.5, "opacity": 1.5})"), "/materials/m/opacity", "1.5");
  expect(error(R"({"type": "diffuse", "reflectance": 0.5, "opacity": true})"), "/materials/m/opacity", "expected an opacity");
  expect(error(R"({"type": "diffuse", "reflectance": 0.5, "emission": 1, "opacity": 0.5})"), "/materials/m/opacity",
         "emitting");
  expect(error(R"({"type": "dielectric", "priority": 1, "opacity": 0.5})"), "/materials/m/opacity", "bounds a medium");
  expect(error(R"({"type": "emissive", "radiance": 1, "opacity": 0.5})"), "/materials/m/opacity", "opacity");
  expect(error(R"({"type": "diffuse", "reflectance": 0.5, "opacity": "broken.png"})"), "/materials/m/opacity",
         "cannot use the opacity image");
  expect(error(R"({"type": "diffuse", "reflectance": 0.5, "opacity": "mask.png"})",
               R"({"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"})"),
         "/shapes/0", "no texture coordinates");
  expect(error(R"({"type": "diffuse", "reflectance": 0.5, "opacity": "mask.png"})",
               R"({"type": "box", "min": [0, 0, 0], "max": [1, 1, 1], "material": "m"})"),
         "/shapes/0", "no texture coordinates");
  expect(error(R"({"type": "diffuse", "reflectance": 0.5, "opacity": 0.5})",
               R"({"type": "box", "min": [0, 0, 0], "max": [1, 1, 1], "material": "m", "holdout": true})"),
         "/shapes/0", "holdout");
}

}  // namespace
}  // namespace caligo
