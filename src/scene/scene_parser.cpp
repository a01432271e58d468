#include "scene/scene_parser.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/math.h"
#include "scene/json_reader.h"
#include "scene/transform_parser.h"
#include "scene/volume_parser.h"

namespace caligo {
namespace {

namespace fs = std::filesystem;

constexpr double kMaxResolution = 16384;
constexpr double kMaxSpp = 1'000'000;
constexpr double kMaxDepth = 10'000;
constexpr double kMaxIor = 10;
constexpr double kMaxAngle = 179;         // spot cone half-angles, degrees
constexpr double kMaxAngularRadius = 45;  // directional light, degrees
// Two unit vectors closer than this (|cross|, i.e. the sine of their angle) count as parallel.
constexpr float kParallelSine = 1e-4f;

// ---- shared checks ----

// The direction from `from` to the point at `target`, which must differ from `from`.
Vec3 read_target_direction(const JsonCursor& target, Vec3 from, std::string_view from_name) {
  const Vec3 to = target.vec3();
  if (!(length_squared(to - from) > 0.0f))
    target.fail("expected a point different from " + std::string(from_name) + " " + format_vec3(from) +
                ", got the same point");
  return normalize(to - from);
}

bool parallel(Vec3 a, Vec3 b) { return length(cross(normalize(a), normalize(b))) < kParallelSine; }

// corner + s*edge1 + t*edge2: both edges non-zero and not parallel.
void read_parallelogram(ObjectReader& r, Vec3& corner, Vec3& edge1, Vec3& edge2) {
  corner = r.vec3("corner");
  const JsonCursor c1 = r.required("edge1"), c2 = r.required("edge2");
  edge1 = c1.vec3();
  edge2 = c2.vec3();
  if (!(length_squared(edge1) > 0.0f)) c1.fail("expected a non-zero edge, got " + c1.describe());
  if (!(length_squared(edge2) > 0.0f)) c2.fail("expected a non-zero edge, got " + c2.describe());
  if (parallel(edge1, edge2))
    c2.fail("expected edge2 not parallel to edge1 " + format_vec3(edge1) + ", got " + c2.describe() +
            " (the area would be zero)");
}

// ---- camera and render settings ----

Vec2i read_resolution(const JsonCursor& c) {
  if (!c.is_array() || c.json().size() != 2)
    c.fail("expected an array of 2 integers [width, height], got " + c.describe());
  const auto e = c.elements("");
  const Range side = Range::closed(1, kMaxResolution);
  return {int(e[0].integer(side)), int(e[1].integer(side))};
}

CameraDesc parse_camera(const JsonCursor& c) {
  ObjectReader r(c, "the camera");
  r.allow({"position", "look_at", "up", "fov", "resolution"});
  CameraDesc camera;
  camera.position = r.vec3("position");
  const JsonCursor look_at = r.required("look_at");
  const Vec3 view = read_target_direction(look_at, camera.position, "position");
  camera.look_at = look_at.vec3();
  if (auto up = r.optional("up")) {
    camera.up = read_direction(*up);
    if (parallel(camera.up, view))
      up->fail("expected an up vector not parallel to the view direction " + format_vec3(view) + ", got " +
               up->describe());
  } else if (parallel(camera.up, view)) {
    r.fail("the view direction " + format_vec3(view) +
           " is parallel to the default up [0, 1, 0]; give \"up\"");
  }
  camera.fov_degrees = r.number_or("fov", camera.fov_degrees, Range::open(0, 180));
  if (auto res = r.optional("resolution")) camera.resolution = read_resolution(*res);
  r.finish();
  return camera;
}

RenderDefaults parse_render(const JsonCursor& c) {
  ObjectReader r(c, "the render settings");
  r.allow({"spp", "max_depth", "max_volume_bounces", "seed"});
  RenderDefaults render;
  render.spp = int(r.integer_or("spp", render.spp, Range::closed(1, kMaxSpp)));
  render.max_depth = int(r.integer_or("max_depth", render.max_depth, Range::closed(0, kMaxDepth)));
  render.max_volume_bounces =
      int(r.integer_or("max_volume_bounces", render.max_volume_bounces, Range::closed(0, kMaxDepth)));
  if (auto seed = r.optional("seed")) render.seed = seed->unsigned_integer();
  r.finish();
  return render;
}

// ---- materials ----

Material parse_material(const JsonCursor& c, const std::string& name) {
  ObjectReader r(c, "a material");
  const std::string type = r.choice("type", {"diffuse", "dielectric", "emissive", "null"});
  r.set_what("a " + type + " material");
  Material m;
  m.name = name;
  if (type == "diffuse") {
    r.allow({"type", "reflectance", "emission", "two_sided"});
    m.bsdf = DiffuseBsdf{r.rgb("reflectance", Range::closed(0, 1))};
    m.emission = r.rgb_or("emission", RGB(0.0f));
    m.two_sided_emission = r.boolean_or("two_sided", false);
  } else if (type == "dielectric") {
    r.allow({"type", "ior"});
    m.bsdf = DielectricBsdf{r.number_or("ior", 1.5f, Range::closed(1, kMaxIor))};
  } else if (type == "emissive") {
    r.allow({"type", "radiance", "color", "two_sided"});
    m.bsdf = BlackBsdf{};
    const RGB color = r.rgb_or("color", RGB(1.0f));
    m.emission = color * r.rgb("radiance");
    m.two_sided_emission = r.boolean_or("two_sided", false);
  } else {
    r.allow({"type"});
    m.bsdf = NullBsdf{};
  }
  r.finish();
  return m;
}

std::vector<Material> parse_materials(const JsonCursor& c) {
  std::vector<Material> materials;
  for (const auto& [name, m] : named_definitions(c, "material", "materials"))
    materials.push_back(parse_material(m, name));
  return materials;
}

int find_material(const JsonCursor& c, const std::vector<Material>& materials) {
  std::vector<std::string> names;
  for (const Material& m : materials) names.push_back(m.name);
  return int(find_definition(c, names, "material", "materials"));
}

// ---- shapes ----

std::string resolve_path(const std::string& file, const std::string& base_dir) {
  fs::path p(file);
  if (p.is_relative() && !base_dir.empty()) p = fs::path(base_dir) / p;
  return p.lexically_normal().string();
}

MeshFileShape read_mesh(ObjectReader& r, const std::string& base_dir) {
  const JsonCursor c = r.required("file");
  const std::string file = c.string();
  std::string ext = fs::path(file).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char ch) { return char(std::tolower(ch)); });
  if (ext != ".obj" && ext != ".gltf" && ext != ".glb")
    c.fail("expected a mesh file ending in .obj, .gltf or .glb, got " + c.describe());
  return {resolve_path(file, base_dir), r.boolean_or("skip_degenerate", false)};
}

ShapeGeometry read_geometry(ObjectReader& r, const std::string& type, const std::string& base_dir) {
  if (type == "sphere") {
    r.allow({"type", "center", "radius", "material", "transform"});
    const Vec3 center = r.vec3("center");
    return SphereShape{center, r.number("radius", size_range())};
  }
  if (type == "box") {
    r.allow({"type", "min", "max", "material", "transform"});
    const BoxCorners box = read_box_corners(r);
    return BoxShape{box.min, box.max};
  }
  if (type == "rectangle") {
    r.allow({"type", "corner", "edge1", "edge2", "material", "transform"});
    RectangleShape rect;
    read_parallelogram(r, rect.corner, rect.edge1, rect.edge2);
    return rect;
  }
  r.allow({"type", "file", "skip_degenerate", "material", "transform"});
  return read_mesh(r, base_dir);
}

ShapeDesc parse_shape(const JsonCursor& c, const std::vector<Material>& materials,
                      const std::string& base_dir) {
  ObjectReader r(c, "a shape");
  const std::string type = r.choice("type", {"sphere", "box", "rectangle", "mesh"});
  r.set_what("a " + type + " shape");
  ShapeDesc shape;
  shape.where = c.where();
  shape.geometry = read_geometry(r, type, base_dir);
  shape.material = find_material(r.required("material"), materials);
  if (auto t = r.optional("transform")) shape.transform = parse_transform(*t);
  r.finish();
  return shape;
}

// ---- lights ----

// color x (the direct quantity, or "power" converted with `per_watt`).
RGB read_emission(ObjectReader& r, std::string_view direct_key, float per_watt) {
  const RGB color = r.rgb_or("color", RGB(1.0f));
  const auto [which, c] = r.exactly_one(direct_key, "power");
  const RGB amount = c.rgb();
  return color * (which == 0 ? amount : amount * per_watt);
}

PointLight read_point(ObjectReader& r) {
  r.allow({"type", "position", "color", "intensity", "power"});
  PointLight light;
  light.position = r.vec3("position");
  light.intensity = read_emission(r, "intensity", kInv4Pi);  // P = 4 pi I
  return light;
}

SpotLight read_spot(ObjectReader& r) {
  r.allow({"type", "position", "look_at", "direction", "inner_angle", "outer_angle", "color", "intensity",
           "power"});
  SpotLight light;
  light.position = r.vec3("position");
  const auto [which, aim] = r.exactly_one("look_at", "direction");
  light.direction = which == 0 ? read_target_direction(aim, light.position, "position") : read_direction(aim);
  const JsonCursor inner_c = r.required("inner_angle");
  const float inner = inner_c.number(Range::closed(0, kMaxAngle));
  const float outer = r.number("outer_angle", Range::above_up_to(0, kMaxAngle));
  if (inner > outer)
    inner_c.fail("expected inner_angle <= outer_angle (" + format_number(outer) + "), got " +
                 inner_c.describe());
  light.cos_inner = std::cos(radians(inner));
  light.cos_outer = std::cos(radians(outer));
  // Power of the smoothstep cone (as in pbrt-v4): P = 2 pi I (1 - (cos_inner + cos_outer) / 2).
  const float solid_angle = 2.0f * kPi * (1.0f - 0.5f * (light.cos_inner + light.cos_outer));
  light.intensity = read_emission(r, "intensity", 1.0f / solid_angle);
  return light;
}

SphereLight read_sphere_light(ObjectReader& r) {
  r.allow({"type", "center", "radius", "two_sided", "color", "radiance", "power"});
  SphereLight light;
  light.center = r.vec3("center");
  light.radius = r.number("radius", size_range());
  light.two_sided = r.boolean_or("two_sided", false);
  const float area = 4.0f * kPi * sqr(light.radius);
  const float sides = light.two_sided ? 2.0f : 1.0f;
  light.radiance = read_emission(r, "radiance", 1.0f / (sides * kPi * area));  // P = pi L A per side
  return light;
}

QuadLight read_quad(ObjectReader& r) {
  r.allow({"type", "corner", "edge1", "edge2", "two_sided", "color", "radiance", "power"});
  QuadLight light;
  read_parallelogram(r, light.corner, light.edge1, light.edge2);
  light.two_sided = r.boolean_or("two_sided", false);
  const float area = length(cross(light.edge1, light.edge2));
  const float sides = light.two_sided ? 2.0f : 1.0f;
  light.radiance = read_emission(r, "radiance", 1.0f / (sides * kPi * area));  // P = pi L A per side
  return light;
}

DirectionalLight read_directional(ObjectReader& r) {
  r.allow({"type", "direction", "color", "irradiance", "angular_radius"});
  DirectionalLight light;
  light.direction = read_direction(r.required("direction"));
  const RGB color = r.rgb_or("color", RGB(1.0f));
  light.irradiance = color * r.rgb("irradiance");
  const float angular_radius = r.number_or("angular_radius", 0.0f, Range::closed(0, kMaxAngularRadius));
  light.cos_angular_radius = std::cos(radians(angular_radius));
  return light;
}

EnvironmentLight read_environment(ObjectReader& r) {
  r.allow({"type", "color", "radiance"});
  EnvironmentLight light;
  const RGB color = r.rgb_or("color", RGB(1.0f));
  light.radiance = color * r.rgb("radiance");
  return light;
}

Light parse_light(const JsonCursor& c) {
  ObjectReader r(c, "a light");
  const std::string type =
      r.choice("type", {"point", "spot", "sphere", "quad", "directional", "environment"});
  r.set_what("a " + type + " light");
  Light light;
  if (type == "point") {
    light = read_point(r);
  } else if (type == "spot") {
    light = read_spot(r);
  } else if (type == "sphere") {
    light = read_sphere_light(r);
  } else if (type == "quad") {
    light = read_quad(r);
  } else if (type == "directional") {
    light = read_directional(r);
  } else {
    light = read_environment(r);
  }
  r.finish();
  return light;
}

}  // namespace

SceneDesc parse_scene_text(const std::string& json_text, const std::string& file_label,
                           const std::string& base_dir) {
  const Json root = parse_json_text(json_text, file_label);
  ObjectReader r(JsonCursor(root, file_label, ""), "a scene");
  r.allow({"camera", "render", "materials", "shapes", "lights", "media", "volumes"});
  SceneDesc scene;
  scene.file = file_label;
  scene.camera = parse_camera(r.required("camera"));
  if (auto c = r.optional("render")) scene.render = parse_render(*c);
  if (auto c = r.optional("materials")) scene.materials = parse_materials(*c);
  if (auto c = r.optional("shapes"))
    for (const JsonCursor& s : c->elements("an array of shapes"))
      scene.shapes.push_back(parse_shape(s, scene.materials, base_dir));
  if (auto c = r.optional("lights"))
    for (const JsonCursor& l : c->elements("an array of lights")) scene.lights.push_back(parse_light(l));
  std::vector<NamedMedium> media;
  if (auto c = r.optional("media")) media = parse_media(*c);
  if (auto c = r.optional("volumes"))
    for (const JsonCursor& v : c->elements("an array of volumes"))
      scene.volumes.push_back(parse_volume(v, media));
  r.finish();
  return scene;
}

SceneDesc parse_scene_file(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError({path, ""}, "cannot read the scene file: no such file");
  if (fs::is_directory(path, ec))
    throw InputError({path, ""}, "cannot read the scene file: it is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError({path, ""}, std::string("cannot open the scene file: ") + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError({path, ""}, "cannot read the scene file: read error");
  return parse_scene_text(text.str(), path, fs::path(path).parent_path().string());
}

}  // namespace caligo
