// What the pbrt-v4 importer's two halves share (pbrt_import.cpp reads the directives and
// keeps the graphics state; pbrt_world.cpp turns shapes, materials, lights and media into
// Caligo's scene JSON). Internal to scene_format.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/transform.h"
#include "scene/pbrt_params.h"

namespace caligo::pbrt {

using Json = nlohmann::ordered_json;

[[noreturn]] inline void fail_at(const std::string& where, const std::string& what) {
  throw InputError(SourceLocation{where, ""}, what);
}

Vec3 apply_point(const Mat4& m, Vec3 p);
Vec3 apply_vector(const Mat4& m, Vec3 v);
float determinant3(const Mat4& m);
inline Json to_json(Vec3 v) { return Json::array({v.x, v.y, v.z}); }
inline Json to_json(RGB c) { return Json::array({c.r, c.g, c.b}); }

// A material as declared (Material, MakeNamedMaterial): Caligo's JSON for it, before the
// medium it encloses and the emission of an area light are known.
struct MaterialSpec {
  std::string pbrt_type;  // "diffuse", "dielectric", "interface", ...
  Json json;              // {"type": "diffuse", ...}
};

struct AreaLight {
  RGB radiance;
  bool two_sided = false;
  std::string where;
  double power = -1;  // watts when given: the radiance is scaled to emit it from the shape's area
};

// A named medium as declared: its Caligo medium and, for grid media, the volume that holds it
// (placed by the transform at its declaration).
struct MediumSpec {
  Json medium;
  std::optional<Json> volume;  // grid media: {"type": "dense" | "vdb", ...}
  bool homogeneous = true;
  std::string where;
  bool placed = false;  // its volume (or camera box) has been added
};

struct GraphicsState {
  Mat4 ctm = Mat4::identity();
  bool reverse_orientation = false;
  MaterialSpec material{"diffuse", Json{{"type", "diffuse"}, {"reflectance", 0.5}}};
  std::optional<AreaLight> area_light;
  std::string inside, outside;  // medium names ("" = vacuum)
};

struct Builder {
  Json scene = Json::object();
  std::vector<std::string> warnings;
  // JSON pointers of what the importer wrote, and the pbrt directive each came from (errors the
  // scene parser finds in them are reported there).
  std::vector<std::pair<std::string, std::string>> origins;
  std::map<std::string, MaterialSpec> named_materials;
  std::map<std::string, MediumSpec> media;

  void add_origin(const std::string& pointer, const std::string& where) { origins.emplace_back(pointer, where); }
  // The Caligo material for `spec` as a shape under `state` uses it: enclosing the inside
  // medium (a homogeneous one) and emitting the area light; defined on first use.
  std::string material_for(const MaterialSpec& spec, const GraphicsState& state, const std::string& where);
  // Adds a grid medium's volume, or a box of a homogeneous camera medium, once.
  void place_medium(const std::string& name, const std::string& where, bool around_camera);
};

// pbrt_world.cpp: one directive each.
MaterialSpec read_material(const std::string& type, const ParamList& params, const std::string& where, Builder& b);
void add_shape(const std::string& type, const ParamList& params, const GraphicsState& state, const std::string& where,
               const std::string& base_dir, Builder& b);
void add_light(const std::string& type, const ParamList& params, const GraphicsState& state, const std::string& where,
               const std::string& base_dir, Builder& b);
AreaLight read_area_light(const std::string& type, const ParamList& params, const std::string& where, Builder& b);
MediumSpec read_medium(const std::string& type, const ParamList& params, const Mat4& ctm, const std::string& where,
                       const std::string& base_dir, Builder& b);

}  // namespace caligo::pbrt
