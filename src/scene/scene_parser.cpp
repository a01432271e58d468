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
#include "geometry/mesh_closure.h"
#include "settings/aov.h"
#include "scene/mesh_loader.h"
#include "image/image_read.h"
#include "scene/json_reader.h"
#include "scene/light_parser.h"
#include "scene/material_priority.h"
#include "scene/pbrt_import.h"
#include "scene/settings_parser.h"
#include "scene/shared_readers.h"
#include "scene/transform_parser.h"
#include "scene/volume_parser.h"

namespace caligo {
namespace {

namespace fs = std::filesystem;

// Dielectrics and null boundaries alike: 1 (vacuum) to 10, beyond any real material.
constexpr double kMaxIor = 10;

// ---- materials ----

// "priority": an integer in [0, kMaxPriority] or a level's name.
int read_priority(const JsonCursor& c) {
  if (c.is_string()) {
    if (const auto level = priority_from_name(c.string())) return *level;
    c.fail("unknown priority " + c.describe() + "; valid names: " + priority_names() +
           ", or an integer in [0, " + std::to_string(kMaxPriority) + "]");
  }
  if (!c.is_number())
    c.fail("expected a priority: an integer in [0, " + std::to_string(kMaxPriority) + "] or one of " +
           priority_names() + ", got " + c.describe());
  return int(c.integer(Range::closed(0, kMaxPriority)));
}

// The nested-dielectric keys (media/medium_stack.h): "priority" and "interior".
void read_bounded_medium(ObjectReader& r, const std::string& type, const std::vector<NamedMedium>& media,
                         Material& m) {
  const auto priority = r.optional("priority");
  if (priority) m.priority = read_priority(*priority);
  const auto interior = r.optional("interior");
  if (interior) {
    m.interior = find_medium(*interior, media);
    const NamedMedium& medium = media[size_t(m.interior)];
    if (!is_homogeneous(medium.shader))
      interior->fail("medium " + quote_for_message(medium.name) +
                     " has a falloff or noise, but a surface's interior medium must be homogeneous "
                     "(constant density); only volume primitives may use it");
  }
  if ((interior || m.priority != kPriorityOff) && type != "dielectric" && type != "null")
    (interior ? *interior : *priority)
        .fail(std::string(type == "emissive" ? "an " : "a ") + type + " material cannot bound a medium: only dielectric and null surfaces bound media");
  if (interior && !priority) m.priority = kPriorityNormal;
  // A null surface's IOR is what neighbouring dielectrics see of its medium: without a
  // priority it bounds none, and the value would be silently ignored.
  if (type == "null" && r.has("ior") && m.priority == kPriorityOff)
    r.optional("ior")->fail("an \"ior\" on a null material needs a \"priority\" or an \"interior\" (a null "
                            "surface of priority off bounds no medium)");
  if (interior && m.priority == kPriorityOff)
    priority->fail("expected a priority other than off for a material with an \"interior\" (off objects "
                   "never enter the medium stack), got " + priority->describe());
}

// "opacity": a number in [0, 1] or an image file of a greyscale mask (materials/opacity_map.h), read
// once per scene. Emitters and surfaces that bound media are opaque.
void read_opacity(ObjectReader& r, SceneFiles& files, Material& m) {
  const auto c = r.optional("opacity");
  if (!c) return;
  if (!m.emission.is_black()) c->fail("an emitting surface cannot be partly transparent (\"opacity\")");
  if (m.priority != kPriorityOff)
    c->fail("a surface that bounds a medium (a priority or an interior) cannot be partly transparent");
  if (!c->is_string()) {
    if (!c->is_number()) c->fail("expected an opacity: a number in [0, 1] or an image file, got " + c->describe());
    m.opacity = c->number(Range::closed(0, 1));
    return;
  }
  const std::string path = files.resolve(*c);
  try {
    const Image image = read_image_grey(path);
    m.opacity_map = std::make_shared<const OpacityMap>(image.width(), image.height(),
                                                       std::vector<float>(image.pixels().begin(), image.pixels().end()));
  } catch (const InputError& e) {
    c->fail(std::string("cannot use the opacity image: ") + e.what());
  }
}

Material parse_material(const JsonCursor& c, const std::string& name, const std::vector<NamedMedium>& media,
                        SceneFiles& files) {
  ObjectReader r(c, "a material");
  const std::string type = r.choice("type", {"diffuse", "dielectric", "emissive", "null"});
  r.set_what("a " + type + " material");
  Material m;
  m.name = name;
  if (type == "diffuse") {
    r.allow({"type", "reflectance", "emission", "two_sided", "priority", "interior", "opacity"});
    m.bsdf = DiffuseBsdf{r.rgb("reflectance", Range::closed(0, 1))};
    m.emission = r.rgb_or("emission", RGB(0.0f));
    m.two_sided_emission = r.boolean_or("two_sided", false);
  } else if (type == "dielectric") {
    r.allow({"type", "ior", "priority", "interior", "opacity"});
    m.ior = r.number_or("ior", 1.5f, Range::closed(1, kMaxIor));
    m.bsdf = DielectricBsdf{m.ior};
  } else if (type == "emissive") {
    r.allow({"type", "radiance", "color", "two_sided", "priority", "interior"});
    m.bsdf = BlackBsdf{};
    const RGB color = r.rgb_or("color", RGB(1.0f));
    m.emission = color * r.rgb("radiance");
    m.two_sided_emission = r.boolean_or("two_sided", false);
  } else {
    r.allow({"type", "ior", "priority", "interior"});
    m.bsdf = NullBsdf{};
    m.ior = r.number_or("ior", 1.0f, Range::closed(1, kMaxIor));
  }
  read_bounded_medium(r, type, media, m);
  if (type == "diffuse" || type == "dielectric") read_opacity(r, files, m);
  r.finish();
  return m;
}

std::vector<Material> parse_materials(const JsonCursor& c, const std::vector<NamedMedium>& media,
                                      SceneFiles& files) {
  std::vector<Material> materials;
  for (const auto& [name, m] : named_definitions(c, "material", "materials"))
    materials.push_back(parse_material(m, name, media, files));
  return materials;
}

int find_material(const JsonCursor& c, const std::vector<Material>& materials) {
  std::vector<std::string> names;
  for (const Material& m : materials) names.push_back(m.name);
  return int(find_definition(c, names, "material", "materials"));
}

// ---- shapes ----

MeshFileShape read_mesh(ObjectReader& r, SceneFiles& files) {
  const JsonCursor c = r.required("file");
  const std::string file = c.string();
  std::string ext = fs::path(file).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char ch) { return char(std::tolower(ch)); });
  if (ext != ".obj" && ext != ".gltf" && ext != ".glb" && ext != ".ply" && ext != ".dae" &&
      ext != ".stl" && ext != ".off")
    c.fail("expected a mesh file ending in .obj, .gltf, .glb, .ply, .dae, .stl or .off, got " + c.describe());
  return {files.resolve(c), r.boolean_or("skip_degenerate", false)};
}

// "positions": [x, y, z, ...], "indices": [a, b, c, ...], "normals": as positions (optional),
// checked as a file's mesh is (mesh_loader.h's validation, at the shape's place).
InlineMeshShape read_inline_mesh(ObjectReader& r) {
  const auto floats = [](const JsonCursor& c, const char* what) {
    std::vector<float> out;
    for (const JsonCursor& e : c.elements(what)) out.push_back(e.number());
    if (out.size() % 3 != 0) c.fail(std::string("expected ") + what + " (a multiple of 3 numbers), got " +
                                    std::to_string(out.size()) + " numbers");
    return out;
  };
  auto mesh = std::make_shared<TriangleMesh>();
  const JsonCursor p = r.required("positions");
  const std::vector<float> positions = floats(p, "an array of vertex coordinates");
  if (positions.size() / 3 > kMaxMeshVertices) p.fail("more vertices than meshes may have");
  for (size_t i = 0; i < positions.size(); i += 3) mesh->positions.push_back({positions[i], positions[i + 1], positions[i + 2]});
  const JsonCursor ic = r.required("indices");
  const std::vector<JsonCursor> indices = ic.elements("an array of vertex indices");
  if (indices.size() % 3 != 0 || indices.empty())
    ic.fail("expected a non-empty multiple of 3 vertex indices, got " + std::to_string(indices.size()));
  for (const JsonCursor& e : indices)
    mesh->indices.push_back(uint32_t(e.integer(Range::closed(0, double(mesh->positions.size()) - 1))));
  if (const auto n = r.optional("normals")) {
    const std::vector<float> normals = floats(*n, "an array of normal coordinates");
    if (normals.size() != positions.size()) n->fail("expected one normal per vertex");
    for (size_t i = 0; i < normals.size(); i += 3) mesh->normals.push_back({normals[i], normals[i + 1], normals[i + 2]});
  }
  if (r.boolean_or("skip_degenerate", false)) remove_degenerate_triangles(*mesh);
  if (const std::string problem = validate_mesh(*mesh); !problem.empty()) r.fail("the mesh: " + problem);
  return {std::move(mesh)};
}

ShapeGeometry read_geometry(ObjectReader& r, const std::string& type, SceneFiles& files) {
  if (type == "sphere") {
    r.allow({"type", "center", "radius", "material", "transform", "open", "holdout", "proxy"});
    const Vec3 center = r.vec3("center");
    return SphereShape{center, r.number("radius", size_range())};
  }
  if (type == "box") {
    r.allow({"type", "min", "max", "material", "transform", "open", "holdout", "proxy"});
    const BoxCorners box = read_box_corners(r);
    return BoxShape{box.min, box.max};
  }
  if (type == "rectangle") {
    r.allow({"type", "corner", "edge1", "edge2", "material", "transform", "open", "holdout", "proxy"});
    RectangleShape rect;
    read_parallelogram(r, rect.corner, rect.edge1, rect.edge2);
    return rect;
  }
  r.allow({"type", "file", "generate", "positions", "indices", "normals", "skip_degenerate", "material", "transform",
           "open", "holdout", "proxy"});
  if (r.has("positions")) {
    if (r.has("file") || r.has("generate")) r.fail("a mesh takes one of \"file\", \"generate\" or \"positions\"");
    return read_inline_mesh(r);
  }
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
  return read_mesh(r, files);
}

// The open-surface rule: a surface whose material has a priority bounds a medium, so it must be
// closed unless the scene says "open": true (a water plane: the medium lies behind its normal).
// Spheres, boxes and generated meshes are closed; a rectangle is open; a mesh file is loaded
// now and its edges counted (mesh_closure.h).
void check_closed(const ObjectReader& r, const ShapeDesc& shape, const Material& material) {
  if (material.priority == kPriorityOff) return;
  const std::string bounds = "material " + quote_for_message(material.name) + " bounds a medium but ";
  const std::string fix = "; close it or mark the shape \"open\": true";
  if (std::holds_alternative<RectangleShape>(shape.geometry)) r.fail(bounds + "a rectangle is open" + fix);
  const auto* file = std::get_if<MeshFileShape>(&shape.geometry);
  const auto* inline_mesh = std::get_if<InlineMeshShape>(&shape.geometry);
  if (!file && !inline_mesh) return;
  const TriangleMesh mesh =
      inline_mesh ? *inline_mesh->mesh
                  : load_mesh(file->path, shape.where,
                              file->skip_degenerate ? DegenerateTriangles::kRemove : DegenerateTriangles::kReject);
  const MeshClosure c = check_closure(mesh);
  if (c.boundary_edges > 0)
    r.fail(bounds + "this mesh is open (" + std::to_string(c.boundary_edges) + " boundary edges)" + fix);
  if (c.non_manifold_edges > 0)
    r.fail(bounds + "this mesh is not a closed surface (" + std::to_string(c.non_manifold_edges) +
           " edges shared by more than two triangles)" + fix);
  if (c.misoriented_edges > 0)
    r.fail(bounds + "this mesh is inconsistently oriented (" + std::to_string(c.misoriented_edges) +
           " edges whose two triangles wind the same way); fix its winding or mark the shape \"open\": true");
}

// "proxy": a closed shape (sphere, box or mesh, with its own geometry keys only) for the hybrid's
// shadow volumes; closure of a mesh file is checked when the scene is built.
ShapeGeometry parse_proxy(const JsonCursor& c, SceneFiles& files) {
  ObjectReader r(c, "a shadow proxy");
  const std::string type = r.choice("type", {"sphere", "box", "mesh"});
  r.set_what("a " + type + " shadow proxy");
  ShapeGeometry geometry = read_geometry(r, type, files);
  for (const char* key : {"material", "transform", "open", "holdout", "proxy"})
    if (r.has(key))
      r.optional(key)->fail(std::string("a shadow proxy takes its shape's material and transform; \"") + key +
                            "\" does not belong here");
  r.finish();
  return geometry;
}

ShapeDesc parse_shape(const JsonCursor& c, const std::vector<Material>& materials, SceneFiles& files) {
  ObjectReader r(c, "a shape");
  const std::string type = r.choice("type", {"sphere", "box", "rectangle", "mesh"});
  r.set_what("a " + type + " shape");
  ShapeDesc shape;
  shape.where = c.where();
  shape.geometry = read_geometry(r, type, files);
  shape.material = find_material(r.required("material"), materials);
  if (auto t = r.optional("transform")) shape.transform = parse_transform(*t);
  const bool open = r.boolean_or("open", false);
  if (!open) check_closed(r, shape, materials[size_t(shape.material)]);
  shape.holdout = r.boolean_or("holdout", false);
  if (auto p = r.optional("proxy")) shape.proxy = parse_proxy(*p, files);
  r.finish();
  return shape;
}

}  // namespace

SceneDesc parse_scene_text(const std::string& json_text, const std::string& file_label,
                           const std::string& base_dir, std::optional<int> frame) {
  const Json root = parse_json_text(json_text, file_label);
  ObjectReader r(JsonCursor(root, file_label, ""), "a scene");
  r.allow({"camera", "render", "realtime", "materials", "shapes", "lights", "media", "volumes"});
  SceneDesc scene;
  scene.file = file_label;
  SceneFiles files{base_dir, {}, {}, frame};
  scene.camera = parse_camera(r.required("camera"));
  if (auto c = r.optional("render")) scene.render = parse_render(*c);
  if (auto c = r.optional("realtime")) scene.realtime = parse_realtime(*c);
  // Media first: materials name their interior medium.
  if (auto c = r.optional("media")) scene.media = parse_media(*c);
  if (auto c = r.optional("materials")) scene.materials = parse_materials(*c, scene.media, files);
  if (auto c = r.optional("shapes"))
    for (const JsonCursor& s : c->elements("an array of shapes"))
      scene.shapes.push_back(parse_shape(s, scene.materials, files));
  if (auto c = r.optional("lights")) {
    LightFileCache cache{files, {}, {}, {}};
    for (const JsonCursor& l : c->elements("an array of lights")) {
      ParsedLight parsed = parse_light(l, cache);
      scene.lights.push_back(std::move(parsed.light));
      scene.light_options.push_back(std::move(parsed.options));
    }
  }
  if (auto c = r.optional("volumes"))
    for (const JsonCursor& v : c->elements("an array of volumes"))
      scene.volumes.push_back(parse_volume(v, scene.media, files));
  r.finish();
  scene.files = std::move(files.named);
  scene.warnings = std::move(files.warnings);
  return scene;
}

SceneDesc parse_scene_file(const std::string& path, std::optional<int> frame) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError({path, ""}, "cannot read the scene file: no such file");
  if (fs::is_directory(path, ec))
    throw InputError({path, ""}, "cannot read the scene file: it is a directory");
  if (is_pbrt_path(path)) return parse_pbrt_file(path);
  // Refused before reading: a huge file would be read whole into memory first.
  if (const auto size = fs::file_size(path, ec); !ec && size > kMaxJsonBytes)
    throw InputError({path, ""}, "the scene file is " + std::to_string(size) +
                                     " bytes; scene files are limited to " + std::to_string(kMaxJsonBytes) +
                                     " bytes (64 MiB)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError({path, ""}, std::string("cannot open the scene file: ") + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError({path, ""}, "cannot read the scene file: read error");
  return parse_scene_text(text.str(), path, fs::path(path).parent_path().string(), frame);
}

}  // namespace caligo
