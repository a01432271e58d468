// Nested dielectrics in the scene format: "priority", "interior" and "ior" on materials, the
// open-surface rule on shapes, "priority_shadows" (docs/scene-format.md "Media inside surfaces").
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "media/medium_stack.h"
#include "scene/scene_parser.h"

namespace caligo {
namespace {

namespace fs = std::filesystem;
using OJson = nlohmann::ordered_json;

// A glass of water: every new key in use.
OJson water_scene() {
  return OJson::parse(R"json({
    "camera": {"position": [0, 1, 5], "look_at": [0, 0, 0]},
    "render": {"priority_shadows": true},
    "materials": {
      "glass": {"type": "dielectric", "ior": 1.5, "priority": "high"},
      "water": {"type": "dielectric", "ior": 1.33, "interior": "water"},
      "clip": {"type": "null", "priority": 50},
      "tinted": {"type": "null", "ior": 1.2, "interior": "dye", "priority": 7},
      "white": {"type": "diffuse", "reflectance": 0.5, "priority": "off"}
    },
    "media": {
      "water": {"sigma_a": [0.3, 0.05, 0.04]},
      "dye": {"sigma_s": 1, "sigma_a": 0.1},
      "puff": {"sigma_s": 1, "falloff": {"exponent": 2}}
    },
    "shapes": [
      {"type": "box", "min": [-1, 0, -1], "max": [1, 2, 1], "material": "glass"},
      {"type": "sphere", "center": [0, 1, 0], "radius": 0.9, "material": "water"},
      {"type": "rectangle", "corner": [-5, 0.5, 5], "edge1": [10, 0, 0], "edge2": [0, 0, -10],
       "material": "clip", "open": true},
      {"type": "mesh", "generate": {"kind": "sphere"}, "material": "tinted"},
      {"type": "rectangle", "corner": [-5, 0, 5], "edge1": [10, 0, 0], "edge2": [0, 0, -10], "material": "white"}
    ],
    "volumes": [{"type": "sphere", "center": [3, 1, 0], "radius": 1, "medium": "puff"},
                {"type": "sphere", "center": [-3, 1, 0], "radius": 1, "medium": "dye"}]
  })json");
}

SceneDesc parse(const OJson& j) { return parse_scene_text(j.dump(), "w.json", ""); }

std::string error_of(const OJson& j) {
  try {
    parse(j);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

const Material& material(const SceneDesc& s, const std::string& name) {
  for (const Material& m : s.materials)
    if (m.name == name) return m;
  throw std::runtime_error("no material " + name);
}

TEST(PriorityParser, MaterialsBoundMedia) {
  const SceneDesc s = parse(water_scene());
  ASSERT_EQ(s.media.size(), 3u);
  EXPECT_EQ(s.media[0].name, "water");
  EXPECT_EQ(s.media[0].shader.sigma_a, RGB(0.3f, 0.05f, 0.04f));
  EXPECT_TRUE(s.render.path.priority_shadows);

  const Material& glass = material(s, "glass");
  EXPECT_EQ(glass.priority, kPriorityHigh);
  EXPECT_EQ(glass.interior, -1);  // a priority without an interior: vacuum inside
  EXPECT_FLOAT_EQ(glass.ior, 1.5f);
  EXPECT_FLOAT_EQ(std::get<DielectricBsdf>(glass.bsdf).ior, 1.5f);

  const Material& water = material(s, "water");
  EXPECT_EQ(water.priority, kPriorityNormal);  // an interior without a priority: normal
  EXPECT_EQ(water.interior, 0);
  EXPECT_FLOAT_EQ(water.ior, 1.33f);
  EXPECT_FLOAT_EQ(std::get<DielectricBsdf>(water.bsdf).ior, 1.33f);

  const Material& clip = material(s, "clip");
  EXPECT_EQ(clip.priority, 50);
  EXPECT_EQ(clip.interior, -1);
  EXPECT_FLOAT_EQ(clip.ior, 1.0f);  // a null material's default

  const Material& tinted = material(s, "tinted");
  EXPECT_EQ(tinted.priority, 7);
  EXPECT_EQ(tinted.interior, 1);
  EXPECT_FLOAT_EQ(tinted.ior, 1.2f);
  EXPECT_TRUE(std::holds_alternative<NullBsdf>(tinted.bsdf));

  EXPECT_EQ(material(s, "white").priority, kPriorityOff);
}

TEST(PriorityParser, VolumesRecordTheirMedium) {
  const SceneDesc s = parse(water_scene());
  ASSERT_EQ(s.volumes.size(), 2u);
  EXPECT_EQ(s.volumes[0].medium, 2);
  EXPECT_EQ(s.volumes[1].medium, 1);
  EXPECT_FALSE(is_homogeneous(s.volumes[0].shader));  // a volume primitive may use any medium
}

TEST(PriorityParser, NamedAndNumericPriorities) {
  for (const auto& [value, expected] :
       std::vector<std::pair<OJson, int>>{{"off", 0},        {"very_high", 50}, {"high", 100}, {"normal", 200},
                                          {"low", 300},      {"very_low", 400}, {0, 0},        {1, 1},
                                          {100000, 100000}, {250.0, 250}}) {
    OJson j = water_scene();
    j["materials"]["glass"]["priority"] = value;
    EXPECT_EQ(material(parse(j), "glass").priority, expected) << value;
  }
}

TEST(PriorityParser, MaterialsWithoutTheNewKeysAreUnchanged) {
  OJson j = water_scene();
  j["materials"]["glass"].erase("priority");
  j["render"].erase("priority_shadows");
  const SceneDesc s = parse(j);
  const Material& glass = material(s, "glass");
  EXPECT_EQ(glass.priority, kPriorityOff);
  EXPECT_EQ(glass.interior, -1);
  EXPECT_FLOAT_EQ(glass.ior, 1.5f);
  EXPECT_FALSE(s.render.path.priority_shadows);
  j["materials"]["plain"] = {{"type", "dielectric"}};
  j["materials"]["portal"] = {{"type", "null"}};
  const SceneDesc t = parse(j);
  EXPECT_FLOAT_EQ(material(t, "plain").ior, 1.5f);
  EXPECT_EQ(material(t, "portal").priority, kPriorityOff);
  EXPECT_FLOAT_EQ(material(t, "portal").ior, 1.0f);
}

// Parsing the materials again from what was parsed gives the same materials.
TEST(PriorityParser, MaterialRoundTrip) {
  const SceneDesc s = parse(water_scene());
  OJson j = water_scene();
  OJson materials = OJson::object();
  for (const Material& m : s.materials) {
    OJson e;
    if (const auto* d = std::get_if<DielectricBsdf>(&m.bsdf)) {
      e = {{"type", "dielectric"}, {"ior", d->ior}};
    } else if (std::holds_alternative<NullBsdf>(m.bsdf)) {
      e = {{"type", "null"}, {"ior", m.ior}};
    } else {
      e = {{"type", "diffuse"}, {"reflectance", std::get<DiffuseBsdf>(m.bsdf).reflectance[0]}};
    }
    e["priority"] = m.priority;
    if (m.interior >= 0) e["interior"] = s.media[size_t(m.interior)].name;
    materials[m.name] = e;
  }
  j["materials"] = materials;
  const SceneDesc t = parse(j);
  ASSERT_EQ(t.materials.size(), s.materials.size());
  for (size_t i = 0; i < s.materials.size(); ++i) {
    SCOPED_TRACE(s.materials[i].name);
    EXPECT_EQ(t.materials[i].name, s.materials[i].name);
    EXPECT_EQ(t.materials[i].priority, s.materials[i].priority);
    EXPECT_EQ(t.materials[i].interior, s.materials[i].interior);
    EXPECT_FLOAT_EQ(t.materials[i].ior, s.materials[i].ior);
    EXPECT_EQ(t.materials[i].bsdf.index(), s.materials[i].bsdf.index());
  }
}

struct BadCase {
  const char* name;
  std::function<void(OJson&)> edit;
  const char* pointer;
  const char* message;
};

const std::vector<BadCase> kBadCases = {
    {"UnknownInterior", [](OJson& j) { j["materials"]["water"]["interior"] = "watr"; },
     "/materials/water/interior", R"(unknown medium "watr" (did you mean "water"?); defined media: water, dye, puff)"},
    {"InteriorNotAString", [](OJson& j) { j["materials"]["water"]["interior"] = 3; },
     "/materials/water/interior", "expected a string"},
    {"UnknownPriorityName", [](OJson& j) { j["materials"]["glass"]["priority"] = "highest"; },
     "/materials/glass/priority", "unknown priority \"highest\"; valid names: off, very_high, high, normal, low, "
     "very_low"},
    {"NegativePriority", [](OJson& j) { j["materials"]["glass"]["priority"] = -1; },
     "/materials/glass/priority", "expected an integer in [0, 100000], got -1"},
    {"HugePriority", [](OJson& j) { j["materials"]["glass"]["priority"] = 100001; },
     "/materials/glass/priority", "expected an integer in [0, 100000], got 100001"},
    {"FractionalPriority", [](OJson& j) { j["materials"]["glass"]["priority"] = 1.5; },
     "/materials/glass/priority", "expected an integer in [0, 100000], got 1.5"},
    {"BooleanPriority", [](OJson& j) { j["materials"]["glass"]["priority"] = true; },
     "/materials/glass/priority", "expected a priority: an integer in [0, 100000] or one of off, very_high"},
    {"InteriorWithPriorityOff", [](OJson& j) { j["materials"]["water"]["priority"] = "off"; },
     "/materials/water/priority", "expected a priority other than off for a material with an \"interior\""},
    {"InteriorWithPriorityZero", [](OJson& j) { j["materials"]["water"]["priority"] = 0; },
     "/materials/water/priority", "off objects never enter the medium stack"},
    {"DiffusePriority", [](OJson& j) { j["materials"]["white"]["priority"] = "high"; },
     "/materials/white/priority",
     "a diffuse material cannot bound a medium: only dielectric and null surfaces bound media"},
    {"DiffuseInterior", [](OJson& j) { j["materials"]["white"]["interior"] = "water"; },
     "/materials/white/interior", "only dielectric and null surfaces bound media"},
    {"EmissiveInterior",
     [](OJson& j) { j["materials"]["lamp"] = {{"type", "emissive"}, {"radiance", 1}, {"interior", "water"}}; },
     "/materials/lamp/interior", "an emissive material cannot bound a medium"},
    {"InhomogeneousInterior", [](OJson& j) { j["materials"]["water"]["interior"] = "puff"; },
     "/materials/water/interior", "medium \"puff\" has a falloff or noise, but a surface's interior medium must be "
     "homogeneous"},
    {"NoisyInterior",
     [](OJson& j) { j["media"]["water"]["noise"] = {{"scale", 2}}; },
     "/materials/water/interior", "must be homogeneous"},
    {"NullIorBelowOne", [](OJson& j) { j["materials"]["clip"]["ior"] = 0.5; }, "/materials/clip/ior",
     "expected a number in [1, 10], got 0.5"},
    {"NullIorAbsurd", [](OJson& j) { j["materials"]["clip"]["ior"] = 11; }, "/materials/clip/ior",
     "expected a number in [1, 10], got 11"},
    {"NullIorWithoutPriority",
     [](OJson& j) {
       j["materials"]["clip"]["priority"] = "off";
       j["materials"]["clip"]["ior"] = 1.2;
     },
     "/materials/clip/ior", "an \"ior\" on a null material needs a \"priority\" or an \"interior\""},
    {"DielectricIorAbsurd", [](OJson& j) { j["materials"]["glass"]["ior"] = 11; }, "/materials/glass/ior",
     "expected a number in [1, 10], got 11"},
    {"IorOnDiffuse", [](OJson& j) { j["materials"]["white"]["ior"] = 1.5; }, "/materials/white/ior",
     "unknown key \"ior\" in a diffuse material"},
    {"OpenRectangle", [](OJson& j) { j["shapes"][2].erase("open"); }, "/shapes/2",
     "material \"clip\" bounds a medium but a rectangle is open; close it or mark the shape \"open\": true"},
    {"OpenNotABoolean", [](OJson& j) { j["shapes"][2]["open"] = "yes"; }, "/shapes/2/open", "expected true or false"},
    {"PriorityShadowsNotABoolean", [](OJson& j) { j["render"]["priority_shadows"] = 1; },
     "/render/priority_shadows", "expected true or false"},
};

class PriorityBadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(PriorityBadInput, NamesPointerAndProblem) {
  OJson j = water_scene();
  GetParam().edit(j);
  const std::string e = error_of(j);
  EXPECT_NE(e.find(std::string("w.json: ") + GetParam().pointer + ": "), std::string::npos) << e;
  EXPECT_NE(e.find(GetParam().message), std::string::npos) << e;
}

INSTANTIATE_TEST_SUITE_P(PriorityParser, PriorityBadInput, ::testing::ValuesIn(kBadCases),
                         [](const auto& info) { return std::string(info.param.name); });

// Mesh files are loaded and their edges counted when their material bounds a medium.
class PriorityMeshTest : public ::testing::Test {
 protected:
  fs::path dir = fs::temp_directory_path() / ("caligo_priority_" + std::to_string(getpid()));
  void SetUp() override {
    fs::create_directories(dir);
    // A tetrahedron, and the same without its last face (3 boundary edges).
    const std::string v = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n";
    std::ofstream(dir / "closed.obj") << v << "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    std::ofstream(dir / "open.obj") << v << "f 1 3 2\nf 1 2 4\nf 1 4 3\n";
    std::ofstream(dir / "flipped.obj") << v << "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 4 3\n";
  }
  void TearDown() override { fs::remove_all(dir); }
  OJson with_mesh(const std::string& file, const std::string& material) const {
    OJson j = water_scene();
    j["shapes"] = OJson::array();
    j["shapes"].push_back({{"type", "mesh"}, {"file", (dir / file).string()}, {"material", material}});
    return j;
  }
};

TEST_F(PriorityMeshTest, ClosedMeshIsAccepted) {
  EXPECT_EQ(parse(with_mesh("closed.obj", "water")).shapes.size(), 1u);
  EXPECT_EQ(parse(with_mesh("open.obj", "white")).shapes.size(), 1u);  // off: any mesh
}

TEST_F(PriorityMeshTest, OpenMeshIsLocatedWithItsBoundaryEdgeCount) {
  const std::string e = error_of(with_mesh("open.obj", "water"));
  EXPECT_NE(e.find("w.json: /shapes/0: material \"water\" bounds a medium but this mesh is open (3 boundary "
                   "edges); close it or mark the shape \"open\": true"),
            std::string::npos)
      << e;
  OJson j = with_mesh("open.obj", "water");
  j["shapes"][0]["open"] = true;
  EXPECT_EQ(parse(j).shapes.size(), 1u);
}

TEST_F(PriorityMeshTest, InconsistentWindingIsLocated) {
  const std::string e = error_of(with_mesh("flipped.obj", "glass"));
  EXPECT_NE(e.find("w.json: /shapes/0: material \"glass\" bounds a medium but this mesh is inconsistently "
                   "oriented"),
            std::string::npos)
      << e;
}

TEST_F(PriorityMeshTest, ClosedShapesNeedNoMark) {
  OJson j = water_scene();
  j["shapes"][0]["open"] = false;
  j["shapes"][1]["open"] = true;  // allowed, and ignored
  j["shapes"][4]["open"] = true;  // on a shape whose material has no priority too
  EXPECT_EQ(parse(j).shapes.size(), 5u);
}

}  // namespace
}  // namespace caligo
