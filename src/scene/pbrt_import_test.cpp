// The pbrt-v4 importer: located errors and warnings, transforms, the camera's handedness and
// field of view, light and medium conversions (renders are tested in python/tests and cli_test).
#include "scene/pbrt_import.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/math.h"
#include "media/blackbody.h"

namespace caligo {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

constexpr const char* kHeader = "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 45\nWorldBegin\n";

Json convert(const std::string& text) { return Json::parse(convert_pbrt_text(text, "s.pbrt", ".").json); }

std::string error_of(const std::string& text) {
  try {
    parse_pbrt(convert_pbrt_text(text, "s.pbrt", "."), "s.pbrt", ".");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(PbrtImport, ErrorsNameTheFileAndLine) {
  EXPECT_EQ(error_of(std::string(kHeader) + "Shape \"cylinder\"\n").rfind("s.pbrt:4: Shape \"cylinder\" cannot be rendered", 0), 0u)
      << error_of(std::string(kHeader) + "Shape \"cylinder\"\n");
  EXPECT_NE(error_of(std::string(kHeader) + "Frobnicate 1 2\n").find("s.pbrt:4: unknown directive \"Frobnicate\""), std::string::npos);
  EXPECT_NE(error_of(std::string(kHeader) + "Shape \"sphere\" \"float radius\" [ 1\n").find("s.pbrt:4"), std::string::npos);
  EXPECT_NE(error_of(std::string(kHeader) + "Shape \"sphere\" \"float radius\" \"big\"\n").find("expected numbers"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kHeader) + "Shape \"sphere\" \"string radius\" \"2\"\n").find("expected type float"),
            std::string::npos);
  EXPECT_NE(error_of("Shape \"sphere\n").find("s.pbrt:1: a string is not closed"), std::string::npos);
  EXPECT_NE(error_of("Shape \"sphere\"\n").find("s.pbrt:1: Shape must come after WorldBegin"), std::string::npos);
  EXPECT_NE(error_of("LookAt 0 0 5  0 0 0  0 1 0\n").find("no WorldBegin"), std::string::npos);
  EXPECT_NE(error_of(std::string(kHeader) + "ObjectBegin \"tree\"\n").find("s.pbrt: an ObjectBegin is never closed"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kHeader) + "NamedMaterial \"gold\"\n").find("s.pbrt:4: NamedMaterial: no material"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kHeader) + "MediumInterface \"fog\" \"\"\n").find("s.pbrt:4: MediumInterface: medium \"fog\" is not defined"),
            std::string::npos);
  EXPECT_NE(error_of("Include \"no/such/file.pbrt\"\n").find("s.pbrt:1: cannot read"), std::string::npos);
  // Found by the fuzzer: a Latin-1 byte in a string once escaped as an uncaught JSON exception.
  EXPECT_NE(error_of(std::string(kHeader) + "\nMakeNamedMaterial \"caf\xe9\" \"string type\" \"diffuse\"\n")
                .find("s.pbrt:5: a string holds bytes that are not UTF-8"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kHeader) + "Texture \"t\x92\" \"spectrum\" \"imagemap\"\n").find("s.pbrt:4: a string holds bytes"),
            std::string::npos);
}

// What the scene parser refuses in the converted JSON is reported at the pbrt directive.
TEST(PbrtImport, ParserErrorsAreReportedAtTheDirective) {
  const std::string e = error_of(std::string(kHeader) + "\n\nShape \"sphere\" \"float radius\" 1e9\n");
  EXPECT_EQ(e.rfind("s.pbrt:6: ", 0), 0u) << e;
  EXPECT_NE(e.find("/shapes/0/radius"), std::string::npos) << e;
}

TEST(PbrtImport, UnusedParametersAreLocatedWarnings) {
  const PbrtConversion c = convert_pbrt_text(std::string(kHeader) + "Shape \"sphere\" \"float radius\" 2 \"float glow\" 1\n",
                                             "s.pbrt", ".");
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_EQ(c.warnings[0], "s.pbrt:4: Shape \"sphere\": parameter \"float glow\" is not used by Caligo");
}

TEST(PbrtImport, TransformsComposeAsPbrtDoes) {
  // Translate then Scale: the sphere's centre moves by the translation, its radius by the scale.
  Json s = convert(std::string(kHeader) + "AttributeBegin\nTranslate 1 2 3\nScale 2 2 2\nShape \"sphere\" \"float radius\" 0.5\n"
                                          "AttributeEnd\nShape \"sphere\" \"float radius\" 0.25\n");
  EXPECT_EQ(s["shapes"][0]["center"], Json::array({1.0, 2.0, 3.0}));
  EXPECT_EQ(s["shapes"][0]["radius"], 1.0);
  EXPECT_EQ(s["shapes"][1]["center"], Json::array({0.0, 0.0, 0.0}));  // AttributeEnd restored the CTM
  // Transform lists the matrix column by column: the last four numbers are the translation.
  s = convert(std::string(kHeader) + "ConcatTransform [1 0 0 0  0 1 0 0  0 0 1 0  4 5 6 1]\nShape \"sphere\"\n");
  EXPECT_EQ(s["shapes"][0]["center"], Json::array({4.0, 5.0, 6.0}));
  // Rotate 90 about z takes +x to +y.
  s = convert(std::string(kHeader) + "Rotate 90 0 0 1\nTranslate 1 0 0\nShape \"sphere\"\n");
  EXPECT_NEAR(double(s["shapes"][0]["center"][0]), 0.0, 1e-6);
  EXPECT_NEAR(double(s["shapes"][0]["center"][1]), 1.0, 1e-6);
  EXPECT_NE(error_of(std::string(kHeader) + "Scale 1 2 1\nShape \"sphere\"\n").find("non-uniform scale"), std::string::npos);
}

TEST(PbrtImport, TheCameraKeepsPbrtsHandednessAndShorterSideFov) {
  Json s = convert(kHeader);
  EXPECT_EQ(s["camera"]["handedness"], "left");  // pbrt's camera x is up x view: the viewer's left in Caligo's frame
  EXPECT_EQ(s["camera"]["position"], Json::array({0.0, 0.0, 5.0}));
  EXPECT_EQ(s["camera"]["fov"], 45.0);
  // Blender's exporter mirrors x before the LookAt to undo it.
  s = convert("Scale -1 1 1\n" + std::string(kHeader));
  EXPECT_FALSE(s["camera"].contains("handedness"));
  // Portrait: pbrt's fov spans the width, Caligo's the height.
  s = convert("Film \"rgb\" \"integer xresolution\" 100 \"integer yresolution\" 200\n" + std::string(kHeader));
  const double expected = 2 * std::atan(std::tan(radians(45.0f) / 2) * 2.0) * 180 / kPi;
  EXPECT_NEAR(double(s["camera"]["fov"]), expected, 1e-3);
  EXPECT_EQ(s["camera"]["resolution"], Json::array({100, 200}));
}

// ObjectInstance copies the object's shapes, the instance's transform after their own.
TEST(PbrtImport, ObjectInstancesAreExpanded) {
  const std::string tri = "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 2]\n";
  const Json s = convert(std::string(kHeader) + "ObjectBegin \"tri\"\n" + tri + "ObjectEnd\n" +
                         "AttributeBegin\nTranslate 5 0 0\nObjectInstance \"tri\"\nAttributeEnd\nObjectInstance \"tri\"\n");
  ASSERT_EQ(s["shapes"].size(), 2u);
  const Json& moved = s["shapes"][0]["transform"].back()["matrix"];
  EXPECT_EQ(moved[3], 5.0);  // row 0, column 3: the translation
  EXPECT_FALSE(s["shapes"][1].contains("transform"));
  EXPECT_EQ(s["shapes"][1]["positions"], s["shapes"][0]["positions"]);
  // A bad scene in an instance is reported at the shape's directive.
  const std::string bad = "Shape \"sphere\" \"float radius\" 1e9\n";
  EXPECT_EQ(error_of(std::string(kHeader) + "ObjectBegin \"b\"\n" + bad + "ObjectEnd\nObjectInstance \"b\"\n").rfind("s.pbrt:5: ", 0), 0u);
  EXPECT_NE(error_of(std::string(kHeader) + "ObjectInstance \"nope\"\n").find("s.pbrt:4: ObjectInstance: no object \"nope\""),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kHeader) + "ObjectEnd\n").find("s.pbrt:4: ObjectEnd without ObjectBegin"), std::string::npos);
  EXPECT_NE(error_of(std::string(kHeader) + "ObjectBegin \"l\"\nLightSource \"point\"\n").find("s.pbrt:5: LightSource"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kHeader) + "ObjectBegin \"a\"\nObjectBegin \"b\"\n").find("s.pbrt:5: ObjectBegin inside"),
            std::string::npos);
}

// "power" on an area light: radiance x pi x area x sides = power (pbrt-v4's DiffuseAreaLight).
TEST(PbrtImport, AreaLightPowerIsSpreadOverTheShape) {
  const Json s = convert(std::string(kHeader) +
                         "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [1 0.5 0.25] \"float power\" 100\n"
                         "Shape \"sphere\" \"float radius\" 0.5\nAttributeEnd\n"
                         "AttributeBegin\nAreaLightSource \"diffuse\" \"float power\" 10 \"bool twosided\" true\n"
                         "Shape \"bilinearmesh\" \"point3 P\" [0 0 0 2 0 0 0 3 0 2 3 0]\nAttributeEnd\n");
  const auto emission = [&](int i) {
    const Json& m = s["materials"][std::string(s["shapes"][i]["material"])];
    return m.contains("emission") ? m["emission"] : m["radiance"];
  };
  const Json e0 = emission(0), e1 = emission(1);
  ASSERT_TRUE(e0.is_array()) << s["materials"].dump();
  EXPECT_NEAR(double(e0[0]), 100 / (kPi * 4 * kPi * 0.25), 1e-4);
  EXPECT_NEAR(double(e0[1]), 0.5 * 100 / (kPi * 4 * kPi * 0.25), 1e-4);
  EXPECT_NEAR(double(e1.is_array() ? e1[0] : e1), 10 / (2 * kPi * 6), 1e-5);
  EXPECT_NE(error_of(std::string(kHeader) + "AreaLightSource \"diffuse\" \"float power\" 10\n"
                                            "Shape \"plymesh\" \"string filename\" \"x.ply\"\n").find("s.pbrt:5: AreaLightSource"),
            std::string::npos);
}

// An image infinite light keeps its file, pbrt's equal-area projection and the light's frame.
TEST(PbrtImport, ImageInfiniteLightsKeepTheirFrame) {
  const Json s = convert(std::string(kHeader) +
                         "AttributeBegin\nRotate -90 1 0 0\nLightSource \"infinite\" \"string filename\" \"sky.exr\" "
                         "\"float scale\" 2\nAttributeEnd\n");
  const Json& light = s["lights"][0];
  EXPECT_EQ(light["type"], "environment");
  EXPECT_EQ(light["strength"], 2.0);
  EXPECT_EQ(light["map"]["projection"], "equal_area");
  EXPECT_EQ(light["map"]["file"], "./sky.exr");
  const Json& m = light["map"]["transform"][0]["matrix"];
  ASSERT_EQ(m.size(), 16u);
  EXPECT_NEAR(double(m[6]), 1.0, 1e-6);  // row 1, column 2: light +z goes to world +y
  EXPECT_NEAR(double(m[9]), -1.0, 1e-6);
  EXPECT_NE(error_of(std::string(kHeader) + "LightSource \"infinite\" \"string filename\" \"a.exr\" \"float illuminance\" 5\n")
                .find("s.pbrt:4: LightSource \"infinite\": \"illuminance\" with an image"),
            std::string::npos);
}

TEST(PbrtImport, LightsAreScaledAsPbrtScalesThem) {
  Json s = convert(std::string(kHeader) +
                   "LightSource \"point\" \"point3 from\" [1 2 3] \"float power\" 100\n"
                   "LightSource \"infinite\" \"blackbody L\" 6500 \"float scale\" 2\n"
                   "LightSource \"distant\" \"point3 from\" [0 10 0] \"point3 to\" [0 0 0] \"rgb L\" [1 2 3]\n");
  EXPECT_NEAR(double(s["lights"][0]["intensity"]), 100 / (4 * kPi), 1e-5);
  EXPECT_EQ(s["lights"][0]["position"], Json::array({1.0, 2.0, 3.0}));
  const RGB c = blackbody_color(6500);  // luminance 1, as pbrt-v4 normalises a light's spectrum
  EXPECT_FLOAT_EQ(float(s["lights"][1]["color"][0]), c.r);
  EXPECT_FLOAT_EQ(float(s["lights"][1]["radiance"]), 2.0f);
  EXPECT_EQ(s["lights"][2]["direction"], Json::array({0.0, -1.0, 0.0}));
  EXPECT_EQ(s["lights"][2]["color"], Json::array({1.0, 2.0, 3.0}));
}

TEST(PbrtImport, MediaInsideShapesAndAroundTheCamera) {
  const std::string media = "MakeNamedMedium \"fog\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [1 2 3] "
                            "\"rgb sigma_s\" [0.5 0.5 0.5] \"float scale\" 2 \"float g\" 0.4\n";
  // A dielectric around the medium encloses it; the camera is outside everything.
  Json s = convert(std::string(kHeader) + media +
                   "MediumInterface \"fog\" \"\"\nMaterial \"dielectric\" \"float eta\" 1.33\nShape \"sphere\"\n");
  EXPECT_EQ(s["materials"]["m0"]["interior"], "fog");
  EXPECT_EQ(s["media"]["fog"]["sigma_a"], Json::array({2.0, 4.0, 6.0}));
  EXPECT_EQ(s["media"]["fog"]["phase"]["g"], 0.4);
  EXPECT_FALSE(s.contains("volumes"));
  // The camera's own medium, bounded by nothing, fills space.
  s = convert(media + "MediumInterface \"\" \"fog\"\n" + kHeader);
  ASSERT_EQ(s["volumes"].size(), 1u);
  EXPECT_EQ(s["volumes"][0]["medium"], "fog");
  EXPECT_EQ(s["volumes"][0]["max"], Json::array({5e4, 5e4, 5e4}));
  // A grid medium becomes a dense volume clipped to its bounds; its interface shape is dropped.
  s = convert(std::string(kHeader) +
              "MakeNamedMedium \"g\" \"string type\" \"uniformgrid\" \"integer nx\" 2 \"integer ny\" 1 \"integer nz\" 1 "
              "\"float density\" [0.5 1]\nMediumInterface \"g\" \"\"\nMaterial \"interface\"\nShape \"sphere\"\n");
  EXPECT_FALSE(s.contains("shapes"));
  EXPECT_EQ(s["volumes"][0]["type"], "dense");
  EXPECT_EQ(s["volumes"][0]["values"], Json::array({0.5, 1.0}));
  EXPECT_EQ(s["volumes"][0]["clip"]["max"], Json::array({2, 1, 1}));
  // An rgbgrid whose voxels share their colours is a density times one sigma_a and one sigma_s.
  const std::string rgbgrid = "MakeNamedMedium \"r\" \"string type\" \"rgbgrid\" \"integer nx\" 2 \"integer ny\" 1 "
                              "\"integer nz\" 1 \"float scale\" 2 \"rgb sigma_a\" [0.1 0.2 0.3 0.2 0.4 0.6] \"rgb sigma_s\" ";
  const std::string use = "\nMediumInterface \"r\" \"\"\nMaterial \"interface\"\nShape \"sphere\"\n";
  s = convert(std::string(kHeader) + rgbgrid + "[0.5 0.5 0.5 1 1 1]" + use);
  const Json& values = s["volumes"][0]["values"];
  ASSERT_EQ(values.size(), 2u);
  EXPECT_NEAR(double(values[0]), 0.7, 1e-6);
  EXPECT_NEAR(double(values[1]), 1.4, 1e-6);
  EXPECT_NEAR(double(s["media"]["r"]["sigma_a"][2]) * double(values[1]), 2 * 0.6, 1e-5);  // the scale too
  EXPECT_NEAR(double(s["media"]["r"]["sigma_s"][0]) * double(values[0]), 2 * 0.5, 1e-5);
  // Voxels of different colours cannot be one density: refused at the directive.
  EXPECT_NE(error_of(std::string(kHeader) + rgbgrid + "[0.5 0.5 0.5 1 0 1]" + use).find("s.pbrt:4: MakeNamedMedium \"rgbgrid\": voxel"),
            std::string::npos);
}

TEST(PbrtImport, IncludeIsRelativeToTheIncludingFile) {
  const fs::path dir = fs::temp_directory_path() / ("caligo_pbrt_" + std::to_string(::getpid()));
  fs::create_directories(dir / "parts");
  std::ofstream(dir / "main.pbrt") << kHeader << "Include \"parts/lights.pbrt\"\n";
  std::ofstream(dir / "parts" / "lights.pbrt") << "Import \"more.pbrt\"\n";
  std::ofstream(dir / "parts" / "more.pbrt") << "\nLightSource \"point\" \"rgb I\" [1 1 1] \"float bogus\" 1\n";
  const PbrtConversion c = convert_pbrt_file((dir / "main.pbrt").string());
  EXPECT_EQ(Json::parse(c.json)["lights"].size(), 1u);
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_EQ(c.warnings[0].rfind((dir / "parts" / "more.pbrt").string() + ":2: ", 0), 0u) << c.warnings[0];
  fs::remove_all(dir);
}

}  // namespace
}  // namespace caligo
