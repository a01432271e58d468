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
#include "scene/light_parser.h"
#include "scene/shared_readers.h"
#include "scene/transform_parser.h"
#include "scene/volume_parser.h"

namespace caligo {
namespace {

namespace fs = std::filesystem;

constexpr double kMaxResolution = 16384;
constexpr double kMaxSpp = 1'000'000;
constexpr double kMaxDepth = 10'000;
constexpr double kMaxIor = 10;
constexpr double kMaxFrames = 100'000;

// ---- camera and render settings ----

Vec2i read_resolution(const JsonCursor& c) {
  if (!c.is_array() || c.json().size() != 2)
    c.fail("expected an array of 2 integers [width, height], got " + c.describe());
  const auto e = c.elements("");
  const Range side = Range::closed(1, kMaxResolution);
  return {int(e[0].integer(side)), int(e[1].integer(side))};
}

Vec3 check_view(const JsonCursor& look_at, Vec3 position) {
  return read_target_direction(look_at, position, "position");
}

// "path": {"interpolation", "keys": [{"time", "position", "look_at"}, ...]}.
void read_camera_path(const JsonCursor& c, CameraDesc& camera) {
  ObjectReader r(c, "a camera path");
  r.allow({"interpolation", "keys"});
  camera.path_interpolation = read_interpolation(r);
  const JsonCursor keys = r.required("keys");
  for (const JsonCursor& k : keys.elements("an array of keys")) {
    ObjectReader kr(k, "a camera key");
    kr.allow({"time", "position", "look_at"});
    CameraKey key;
    key.time = read_key_time(kr, camera.path.empty() ? nullptr : &camera.path.back().time);
    key.position = kr.vec3("position");
    const JsonCursor look_at = kr.required("look_at");
    check_view(look_at, key.position);
    key.look_at = look_at.vec3();
    kr.finish();
    camera.path.push_back(key);
  }
  if (camera.path.empty()) keys.fail("expected at least one key, got an empty array");
  r.finish();
}

void check_up(const CameraDesc& camera, const JsonCursor& where, bool given) {
  auto check = [&](Vec3 view) {
    if (!parallel(camera.up, view)) return;
    if (given)
      where.fail("expected an up vector not parallel to the view direction " + format_vec3(view) + ", got " +
                 where.describe());
    where.fail("the view direction " + format_vec3(view) +
               " is parallel to the default up [0, 1, 0]; give \"up\"");
  };
  check(normalize(camera.look_at - camera.position));
  for (const CameraKey& k : camera.path) check(normalize(k.look_at - k.position));
}

// With a path, "position" and "look_at" may be left out: the first key gives them.
CameraDesc parse_camera(const JsonCursor& c) {
  ObjectReader r(c, "the camera");
  r.allow({"position", "look_at", "up", "fov", "resolution", "path"});
  CameraDesc camera;
  if (auto p = r.optional("path")) read_camera_path(*p, camera);
  const bool still = camera.path.empty();
  if (still || r.has("position")) {
    camera.position = r.vec3("position");
  } else {
    camera.position = camera.path.front().position;
  }
  if (still || r.has("look_at")) {
    const JsonCursor look_at = r.required("look_at");
    check_view(look_at, camera.position);
    camera.look_at = look_at.vec3();
  } else {
    camera.look_at = camera.path.front().look_at;
  }
  const auto up = r.optional("up");
  if (up) camera.up = read_direction(*up);
  check_up(camera, up ? *up : c, up.has_value());
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

RealtimeDefaults parse_realtime(const JsonCursor& c) {
  ObjectReader r(c, "the realtime settings");
  r.allow({"scale", "tile_size", "samples", "gather_radius", "gather_depth_falloff", "temporal",
           "temporal_blend", "multiple_scattering_floor", "steps", "fps", "frames"});
  RealtimeDefaults d;
  if (r.has("scale")) {
    const std::string scale = r.choice("scale", {"full", "half", "quarter"});
    d.scale = scale == "full" ? 1 : (scale == "half" ? 2 : 4);
  }
  d.tile_size = int(r.integer_or("tile_size", d.tile_size, Range::closed(1, 32)));
  d.samples = int(r.integer_or("samples", d.samples, Range::closed(1, 1024)));
  d.gather_radius = int(r.integer_or("gather_radius", d.gather_radius, Range::closed(0, 16)));
  d.gather_depth_falloff = r.number_or("gather_depth_falloff", d.gather_depth_falloff, Range::positive());
  d.temporal = r.boolean_or("temporal", d.temporal);
  d.temporal_blend = r.number_or("temporal_blend", d.temporal_blend, Range::above_up_to(0, 1));
  d.multiple_scattering_floor =
      r.number_or("multiple_scattering_floor", d.multiple_scattering_floor, Range::closed(0, 1));
  if (r.has("steps")) d.equiangular_steps = r.choice("steps", {"uniform", "equiangular"}) == "equiangular";
  d.fps = r.number_or("fps", d.fps, Range::positive());
  d.frames = int(r.integer_or("frames", d.frames, Range::closed(1, kMaxFrames)));
  r.finish();
  return d;
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

MeshFileShape read_mesh(ObjectReader& r, const std::string& base_dir) {
  const JsonCursor c = r.required("file");
  const std::string file = c.string();
  std::string ext = fs::path(file).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char ch) { return char(std::tolower(ch)); });
  if (ext != ".obj" && ext != ".gltf" && ext != ".glb" && ext != ".ply" && ext != ".dae")
    c.fail("expected a mesh file ending in .obj, .gltf, .glb, .ply or .dae, got " + c.describe());
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
  r.allow({"type", "file", "generate", "skip_degenerate", "material", "transform"});
  if (const auto g = r.optional("generate")) {
    if (r.has("file")) r.fail("a mesh takes either \"file\" or \"generate\", not both");
    ObjectReader gr(*g, "a generated mesh");
    gr.allow({"kind", "triangles"});
    GeneratedMeshShape mesh;
    mesh.kind = gr.choice("kind", {"sphere", "torus_knot"}) == "sphere" ? GeneratedMeshShape::Kind::kSphere
                                                                       : GeneratedMeshShape::Kind::kTorusKnot;
    // A subdivided sphere jumps by 4x: 5 million triangles allows its level 8 (1.3 M).
    mesh.triangles = uint64_t(gr.integer_or("triangles", 20000, Range::closed(20, 5e6)));
    gr.finish();
    return mesh;
  }
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

}  // namespace

SceneDesc parse_scene_text(const std::string& json_text, const std::string& file_label,
                           const std::string& base_dir) {
  const Json root = parse_json_text(json_text, file_label);
  ObjectReader r(JsonCursor(root, file_label, ""), "a scene");
  r.allow({"camera", "render", "realtime", "materials", "shapes", "lights", "media", "volumes"});
  SceneDesc scene;
  scene.file = file_label;
  scene.camera = parse_camera(r.required("camera"));
  if (auto c = r.optional("render")) scene.render = parse_render(*c);
  if (auto c = r.optional("realtime")) scene.realtime = parse_realtime(*c);
  if (auto c = r.optional("materials")) scene.materials = parse_materials(*c);
  if (auto c = r.optional("shapes"))
    for (const JsonCursor& s : c->elements("an array of shapes"))
      scene.shapes.push_back(parse_shape(s, scene.materials, base_dir));
  if (auto c = r.optional("lights")) {
    LightFileCache files{base_dir, {}, {}};
    for (const JsonCursor& l : c->elements("an array of lights")) {
      ParsedLight parsed = parse_light(l, files);
      scene.lights.push_back(std::move(parsed.light));
      scene.light_options.push_back(std::move(parsed.options));
    }
  }
  std::vector<NamedMedium> media;
  if (auto c = r.optional("media")) media = parse_media(*c);
  if (auto c = r.optional("volumes"))
    for (const JsonCursor& v : c->elements("an array of volumes"))
      scene.volumes.push_back(parse_volume(v, media, base_dir));
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
