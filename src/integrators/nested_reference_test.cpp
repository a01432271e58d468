// Nested dielectrics and media (media/medium_stack.h) in the reference ladder (reference.h),
// and production (path_tracer.h, visibility.h) held against it. The comparisons measure both
// sides' standard errors from their own samples (per pixel, so the image mean's variance is
// the sum of the pixels' variances of their means) and accept a difference of 1% of the
// mean, with sample counts chosen so that 1% is at least 3 combined standard errors.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/parallel.h"
#include "integrators/ladder_agreement.h"
#include "integrators/path_tracer.h"
#include "integrators/test_scenes.h"
#include "integrators/reference.h"
#include "integrators/visibility.h"
#include "scene/builtins.h"
#include "scene/scene_parser.h"

namespace caligo {
namespace {

// ---- scene building ----

using testing::camera_at;

VolumeShader medium(RGB sigma_a, RGB sigma_s) {
  return VolumeShader{sigma_a, sigma_s, RGB(0.0f), 1.0f, IsotropicPhase{}, ConstantDensity{}, std::nullopt, 0.0f};
}

// Adds a material and returns its index.
int add_material(SceneDesc& desc, Bsdf bsdf, int priority = kPriorityOff, int interior = -1, float ior = 1.0f,
                 RGB emission = RGB(0.0f)) {
  Material m;
  m.name = std::to_string(desc.materials.size());  // (GCC 12 warns falsely on "m" + std::string)
  m.bsdf = bsdf;
  m.emission = emission;
  m.priority = priority;
  m.interior = interior;
  m.ior = ior;
  desc.materials.push_back(m);
  return int(desc.materials.size()) - 1;
}

int add_medium(SceneDesc& desc, const std::string& name, const VolumeShader& shader) {
  desc.media.push_back({name, shader});
  return int(desc.media.size()) - 1;
}

void add_shape(SceneDesc& desc, ShapeGeometry geometry, int material) {
  desc.shapes.push_back({geometry, Transform(), material, {}});
}

// A diffuse wall at z = `z` facing -z (towards cameras on the -z side), 6 m square.
void add_wall(SceneDesc& desc, float z, RGB reflectance) {
  add_shape(desc, RectangleShape{{-3, -3, z}, {0, 6, 0}, {6, 0, 0}}, add_material(desc, DiffuseBsdf{reflectance}));
}

// A UV sphere's triangles (outward winding, or inward when `inward`), appended as OBJ text.
void append_uv_sphere(std::string& obj, int& vertex_base, float radius, bool inward, int rings = 48,
                      int segments = 96) {
  char line[128];
  for (int i = 0; i <= rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const double theta = M_PI * i / rings, phi = 2 * M_PI * j / segments;
      std::snprintf(line, sizeof line, "v %.7f %.7f %.7f\n", radius * std::sin(theta) * std::cos(phi),
                    radius * std::cos(theta), radius * std::sin(theta) * std::sin(phi));
      obj += line;
    }
  const auto v = [&](int i, int j) { return vertex_base + i * segments + (j % segments) + 1; };
  const auto face = [&](int a, int b, int c) {
    std::snprintf(line, sizeof line, "f %d %d %d\n", a, inward ? c : b, inward ? b : c);
    obj += line;
  };
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      // Counter-clockwise seen from outside: (i, j), (i, j + 1), (i + 1, j) with theta down, phi around y.
      if (i > 0) face(v(i, j), v(i, j + 1), v(i + 1, j));
      if (i < rings - 1) face(v(i, j + 1), v(i + 1, j + 1), v(i + 1, j));
    }
  vertex_base += (rings + 1) * segments;
}

using testing::expect_agree;
using testing::Limits;
using testing::str;

// ---- scenes ----

// a. An Off glass sphere (IOR 1.5) in front of a diffuse wall, a quad light above and in
// front of it (out of frame) and a uniform environment.
SceneDesc glass_sphere_scene() {
  SceneDesc desc = camera_at({0, 0, -4}, {0, 0, 0}, {16, 16}, 40.0f);
  add_shape(desc, SphereShape{{0, 0, 0}, 0.7f}, add_material(desc, DielectricBsdf{1.5f}, kPriorityOff, -1, 1.5f));
  add_wall(desc, 1.2f, RGB(0.7f, 0.6f, 0.5f));
  desc.lights.push_back(QuadLight{{-1, 2.5f, -1.5f}, {2, 0, 0}, {0, 0, 2}, RGB(4.0f)});  // faces down
  desc.lights.push_back(EnvironmentLight{RGB(0.2f, 0.25f, 0.3f)});
  return desc;
}

// b. Coloured glass: a priority dielectric sphere whose interior absorbs, in thin fog.
SceneDesc coloured_glass_in_fog_scene() {
  SceneDesc desc = glass_sphere_scene();
  desc.shapes.erase(desc.shapes.begin());
  const int tint = add_medium(desc, "tint", medium(RGB(0.2f, 1.0f, 2.5f), RGB(0.0f)));
  add_shape(desc, SphereShape{{0, 0, 0}, 0.7f}, add_material(desc, DielectricBsdf{1.5f}, kPriorityNormal, tint, 1.5f));
  desc.volumes.push_back({BoxVolumeShape{Transform(), {-5, -5, -5}, {5, 5, 5}},
                          medium(RGB(0.01f), RGB(0.06f))});
  return desc;
}

// c. Subsurface scattering: a dielectric sphere (IOR 1.3) of radius 0.5 m filled with a dense
// medium (extinction 20/m, albedo 0.9), lit from behind by a quad light out of frame.
SceneDesc subsurface_scene() {
  SceneDesc desc = camera_at({0, 0, -3}, {0, 0, 0}, {16, 16}, 28.0f);
  const int milk = add_medium(desc, "milk", medium(RGB(2.0f), RGB(18.0f)));
  add_shape(desc, SphereShape{{0, 0, 0}, 0.5f}, add_material(desc, DielectricBsdf{1.3f}, kPriorityNormal, milk, 1.3f));
  desc.lights.push_back(QuadLight{{-1, 1.8f, 0.2f}, {2, 0, 0}, {0, -0.8f, 1.2f}, RGB(6.0f, 5.0f, 4.0f)});
  desc.lights.push_back(EnvironmentLight{RGB(0.05f)});
  return desc;
}

// d. Water in glass: a glass shell (outer radius 0.7, inner 0.62, one mesh, priority high)
// and a water sphere (radius 0.66, priority normal) overlapping the shell's wall, so the
// water's surface inside the glass is a false hit and the glass-water interface refracts
// 1.5 -> 1.33 at the shell's inner surface.
SceneDesc water_in_glass_scene(const std::string& shell_obj) {
  SceneDesc desc = glass_sphere_scene();
  desc.shapes.erase(desc.shapes.begin());
  desc.shapes.push_back(
      {MeshFileShape{shell_obj}, Transform(), add_material(desc, DielectricBsdf{1.5f}, kPriorityHigh, -1, 1.5f), {}});
  const int water = add_medium(desc, "water", medium(RGB(0.6f, 0.15f, 0.05f), RGB(0.3f)));
  add_shape(desc, SphereShape{{0, 0, 0}, 0.66f},
            add_material(desc, DielectricBsdf{1.33f}, kPriorityNormal, water, 1.33f));
  return desc;
}

std::string write_shell_obj() {
  std::string obj;
  int base = 0;
  append_uv_sphere(obj, base, 0.7f, false);
  append_uv_sphere(obj, base, 0.62f, true);
  const std::string path = (std::filesystem::temp_directory_path() / "caligo_nested_shell.obj").string();
  std::ofstream(path) << obj;
  return path;
}

// ---- the priority cubes: which surfaces are seen ----

// Two overlapping null boxes with absorbing interiors: red [-1, 1]^3 (priority high) and blue
// [0, 2] x [-0.8, 0.8]^2 (priority normal; no face coincides with red's, which would leave
// the order of two crossings at one t to the tie-breaking of each query). In the overlap red
// wins, so along x a ray sees red for 2 m and blue only over x in [1, 2]:
// T = exp(-2 sigma_red - sigma_blue), not the sum of both.
const RGB kRed(0.3f, 1.2f, 1.5f), kBlue(1.4f, 0.9f, 0.25f);

SceneDesc priority_cubes_scene() {
  SceneDesc desc = camera_at({0.5f, 0.3f, -4}, {0.5f, 0, 0}, {16, 16}, 50.0f);
  const int red = add_medium(desc, "red", medium(kRed, RGB(0.0f)));
  const int blue = add_medium(desc, "blue", medium(kBlue, RGB(0.0f)));
  add_shape(desc, BoxShape{{-1, -1, -1}, {1, 1, 1}}, add_material(desc, NullBsdf{}, kPriorityHigh, red, 1.0f));
  add_shape(desc, BoxShape{{0, -0.8f, -0.8f}, {2, 0.8f, 0.8f}}, add_material(desc, NullBsdf{}, kPriorityNormal, blue, 1.0f));
  desc.lights.push_back(EnvironmentLight{RGB(1.0f)});
  return desc;
}

RGB exp_of(RGB depth) { return {std::exp(-depth.r), std::exp(-depth.g), std::exp(-depth.b)}; }

TEST(NestedReference, PriorityCubesTransmittance) {
  const SceneDesc desc = priority_cubes_scene();
  const auto scene = Scene::build(desc);
  struct Case {
    Vec3 origin;
    RGB expected;
    const char* what;
  };
  const Case cases[] = {
      {{-3, 0.1f, 0.2f}, exp_of(kRed * 2.0f + kBlue * 1.0f), "from outside"},
      {{0.5f, 0.1f, 0.2f}, exp_of(kRed * 0.5f + kBlue * 1.0f), "from inside the overlap"},
      {{1.5f, 0.1f, 0.2f}, exp_of(kBlue * 0.5f), "from inside blue only"},
  };
  for (const Case& c : cases) {
    const Ray ray{c.origin, {1, 0, 0}, 0.0f, kInfinity};
    const Vec3 end{3, 0.1f, 0.2f};
    const MediumStack stack = scene->stack_at(c.origin);
    const RGB ladder = reference_transmittance(*scene, ray, end.x - c.origin.x, 8, stack);
    // Production's shadow-ray transmittance towards a point light at `end`.
    PathScratch scratch;
    PathCounters counters;
    scratch.stack.assign(stack);
    const LightSample ls{RGB(1.0f), {1, 0, 0}, end.x - c.origin.x, 1.0f, true};
    const RGB production = light_transmittance(*scene, c.origin, c.origin, ls, true, 0.5f, scratch, counters);
    std::printf("  [%s] expected %s ladder %s production %s\n", c.what, str(c.expected).c_str(), str(ladder).c_str(),
                str(production).c_str());
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(ladder[k], c.expected[k], 1e-4f * std::max(1.0f, c.expected[k])) << c.what;
      // Production stops kShadowEpsilon short of the light: the last 0.01% of the ray is missing.
      EXPECT_NEAR(production[k], c.expected[k], 2e-3f * c.expected[k] + 1e-6f) << c.what;
    }
  }
}

// The same scene seen by the camera against a white environment: both estimators see the
// environment through the boxes with the medium the rules give each stretch.
TEST(NestedReference, PriorityCubesImage) {
  const auto scene = Scene::build(priority_cubes_scene());
  expect_agree(*scene, 1024, 4096, {}, "priority cubes");
}

TEST(NestedReference, OffGlassSphere) {
  const auto scene = Scene::build(glass_sphere_scene());
  expect_agree(*scene, 4096, 4096, {}, "a. Off glass sphere");
}

TEST(NestedReference, ColouredGlassInFog) {
  const auto scene = Scene::build(coloured_glass_in_fog_scene());
  expect_agree(*scene, 4096, 4096, {}, "b. coloured glass in fog");
}

TEST(NestedReference, Subsurface) {
  const auto scene = Scene::build(subsurface_scene());
  expect_agree(*scene, 8192, 8192, {}, "c. subsurface");
}

TEST(NestedReference, WaterInGlass) {
  const auto scene = Scene::build(water_in_glass_scene(write_shell_obj()));
  expect_agree(*scene, 4096, 4096, {}, "d. water in glass");
}

// The built-ins of the issue, at low resolution: glass-of-water (glass, overlapping water, ice)
// and sss (the duck, a dense scattering interior behind a dielectric, lit from behind).
SceneDesc small_builtin(const char* name, Vec2i resolution) {
  SceneDesc desc = parse_builtin(*find_builtin(name));
  desc.camera.resolution = resolution;
  return desc;
}

TEST(NestedReference, GlassOfWaterBuiltin) {
  const auto scene = Scene::build(small_builtin("glass-of-water", {16, 12}));
  expect_agree(*scene, 4096, 2048, {}, "glass-of-water");
}

TEST(NestedReference, SssBuiltin) {
  const auto scene = Scene::build(small_builtin("sss", {16, 12}));
  expect_agree(*scene, 8192, 8192, {}, "sss");
}

}  // namespace
}  // namespace caligo
