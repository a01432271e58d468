// pbrt-v4's shapes, materials, lights and media as Caligo's scene JSON. What Caligo cannot
// honour exactly is a located warning; what it cannot render at all is a located error.
#include <cmath>
#include <filesystem>

#include "core/math.h"
#include "core/message_text.h"
#include "scene/pbrt_builder.h"

namespace caligo::pbrt {
namespace {

namespace fs = std::filesystem;

RGB clamp01(RGB c) { return RGB(std::clamp(c.r, 0.0f, 1.0f), std::clamp(c.g, 0.0f, 1.0f), std::clamp(c.b, 0.0f, 1.0f)); }

// Refractive indices at 587.6 nm (the d line) of pbrt's named glasses; dispersion is not rendered.
double named_glass_ior(const std::string& name) {
  static const std::map<std::string, double> kGlasses = {{"glass-BK7", 1.5168}, {"glass-BAF10", 1.6700},
                                                         {"glass-FK51A", 1.4866}, {"glass-LASF9", 1.8503},
                                                         {"glass-F5", 1.6034}, {"glass-F10", 1.6200},
                                                         {"glass-F11", 1.6209}};
  const auto it = kGlasses.find(name);
  return it == kGlasses.end() ? 0.0 : it->second;
}

double read_eta(const ParamList& p, Builder& b) {
  const Param* eta = p.find("eta");
  if (!eta) return 1.5;
  if (eta->type == "spectrum" && eta->strings.size() == 1) {
    const_cast<Param*>(eta)->used = true;
    const double ior = named_glass_ior(eta->strings[0]);
    if (ior == 0.0) fail_at(eta->where, "eta: unknown named spectrum " + quote_for_message(eta->strings[0]));
    b.warnings.push_back(eta->where + ": eta " + quote_for_message(eta->strings[0]) + " is its index at 587.6 nm (" +
                         std::to_string(ior) + "); dispersion is not rendered");
    return ior;
  }
  return p.number("eta", 1.5);
}

Json diffuse(RGB reflectance) { return Json{{"type", "diffuse"}, {"reflectance", to_json(clamp01(reflectance))}}; }

// ---- Meshes --------------------------------------------------------------------------------

std::vector<Vec3> read_points(const ParamList& p, const char* name, const std::string& where) {
  const std::vector<double> v = p.numbers(name);
  if (v.size() % 3 != 0) fail_at(where, std::string("parameter \"") + name + "\": expected a multiple of 3 numbers");
  std::vector<Vec3> out;
  for (size_t i = 0; i < v.size(); i += 3) out.push_back({float(v[i]), float(v[i + 1]), float(v[i + 2])});
  return out;
}

// A mesh in world space as a Caligo inline mesh; `flip` reverses the winding (pbrt flips the
// normal when ReverseOrientation and a handedness-swapping transform disagree).
Json inline_mesh(std::vector<Vec3> positions, const std::vector<uint32_t>& indices, std::vector<Vec3> normals,
                 const Mat4& ctm, bool flip) {
  Json p = Json::array(), n = Json::array(), idx = Json::array();
  for (Vec3& v : positions) {
    const Vec3 w = apply_point(ctm, v);
    p.insert(p.end(), {w.x, w.y, w.z});
  }
  const std::optional<Mat4> inverse = ctm.inverse();
  for (Vec3& v : normals) {
    const Mat4& inv = *inverse;  // normals go by the inverse transpose
    const Vec3 w{inv.m[0][0] * v.x + inv.m[1][0] * v.y + inv.m[2][0] * v.z,
                 inv.m[0][1] * v.x + inv.m[1][1] * v.y + inv.m[2][1] * v.z,
                 inv.m[0][2] * v.x + inv.m[1][2] * v.y + inv.m[2][2] * v.z};
    const Vec3 u = normalize(w);
    n.insert(n.end(), {u.x, u.y, u.z});
  }
  for (size_t t = 0; t + 2 < indices.size(); t += 3)
    idx.insert(idx.end(), {indices[t], flip ? indices[t + 2] : indices[t + 1], flip ? indices[t + 1] : indices[t + 2]});
  Json mesh{{"type", "mesh"}, {"positions", p}, {"indices", idx}, {"skip_degenerate", true}};
  if (!normals.empty()) mesh["normals"] = n;
  return mesh;
}

std::vector<uint32_t> read_indices(const ParamList& p, size_t vertices, size_t per_face, const std::string& where) {
  std::vector<uint32_t> out;
  if (!p.has("indices")) {
    if (vertices != per_face) fail_at(where, "\"indices\" is required unless the mesh has exactly " + std::to_string(per_face) + " vertices");
    for (uint32_t i = 0; i < per_face; ++i) out.push_back(i);
    return out;
  }
  for (int i : p.integers("indices")) {
    if (size_t(i) >= vertices) fail_at(where, "index " + std::to_string(i) + " is out of range (" + std::to_string(vertices) + " vertices)");
    out.push_back(uint32_t(i));
  }
  if (out.size() % per_face != 0 || out.empty())
    fail_at(where, "expected a multiple of " + std::to_string(per_face) + " indices, got " + std::to_string(out.size()));
  return out;
}

Json disk_mesh(const ParamList& p, const Mat4& ctm, bool flip, const std::string& where) {
  const double height = p.number("height", 0), radius = p.number("radius", 1), inner = p.number("innerradius", 0);
  if (inner != 0.0 || p.number("phimax", 360) != 360.0) fail_at(where, "Shape \"disk\": only whole disks (no innerradius, phimax 360)");
  if (!(radius > 0)) fail_at(where, "Shape \"disk\": radius must be > 0");
  // 256 segments: the polygon's area is within 1e-4 of the disk's.
  constexpr int kSegments = 256;
  std::vector<Vec3> points{{0, 0, float(height)}};
  std::vector<uint32_t> indices;
  for (int i = 0; i < kSegments; ++i) {
    const double a = 2.0 * kPi * i / kSegments;
    points.push_back({float(radius * std::cos(a)), float(radius * std::sin(a)), float(height)});
    indices.insert(indices.end(), {0u, uint32_t(1 + i), uint32_t(1 + (i + 1) % kSegments)});
  }
  return inline_mesh(points, indices, {}, ctm, flip);
}

Json bilinear_mesh(const ParamList& p, const Mat4& ctm, bool flip, const std::string& where, Builder& b) {
  const std::vector<Vec3> points = read_points(p, "P", where);
  const std::vector<uint32_t> quads = read_indices(p, points.size(), 4, where);
  std::vector<uint32_t> triangles;
  bool warped = false;
  for (size_t q = 0; q < quads.size(); q += 4) {
    const uint32_t v00 = quads[q], v10 = quads[q + 1], v01 = quads[q + 2], v11 = quads[q + 3];
    triangles.insert(triangles.end(), {v00, v10, v11, v00, v11, v01});
    const Vec3 n = cross(points[v10] - points[v00], points[v01] - points[v00]);
    const float off = std::abs(dot(points[v11] - points[v00], normalize(n)));
    warped = warped || off > 1e-4f * length(points[v11] - points[v00]);
  }
  if (warped) b.warnings.push_back(where + ": Shape \"bilinearmesh\": non-planar patches become two triangles each");
  return inline_mesh(points, triangles, {}, ctm, flip);
}

bool is_similarity(const Mat4& m, float* scale) {
  const float sx = length(apply_vector(m, {1, 0, 0})), sy = length(apply_vector(m, {0, 1, 0})),
              sz = length(apply_vector(m, {0, 0, 1}));
  *scale = sx;
  return std::abs(sx - sy) <= 1e-4f * sx && std::abs(sx - sz) <= 1e-4f * sx;
}

}  // namespace

MaterialSpec read_material(const std::string& type, const ParamList& p, const std::string& where, Builder& b) {
  const auto warn = [&](const std::string& what) { b.warnings.push_back(where + ": Material \"" + type + "\": " + what); };
  if (type == "diffuse") return {type, diffuse(p.spectrum("reflectance", RGB(0.5f), b.warnings))};
  if (type == "coateddiffuse") {
    warn("approximated by a diffuse surface of its reflectance (the coating's specular layer is left out)");
    return {type, diffuse(p.spectrum("reflectance", RGB(0.5f), b.warnings))};
  }
  if (type == "conductor" || type == "coatedconductor") {
    // Without a reflectance, pbrt's default metal is copper: its normal-incidence colour.
    warn("approximated by a diffuse surface of its reflectance (Caligo has no conductor BSDF)");
    return {type, diffuse(p.spectrum("reflectance", RGB(0.955f, 0.638f, 0.538f), b.warnings))};
  }
  if (type == "diffusetransmission") {
    warn("approximated by a diffuse reflector (no transmission)");
    return {type, diffuse(p.spectrum("reflectance", RGB(0.25f), b.warnings))};
  }
  if (type == "dielectric" || type == "thindielectric") {
    if (type == "thindielectric") warn("approximated by a solid dielectric");
    if (p.number("roughness", 0) != 0 || p.number("uroughness", 0) != 0 || p.number("vroughness", 0) != 0)
      warn("rendered smooth (Caligo's dielectric has no roughness)");
    const double eta = read_eta(p, b);
    if (!(eta >= 1.0 && eta <= 10.0)) fail_at(where, "Material \"dielectric\": eta must be in [1, 10] (Caligo's range)");
    return {type, Json{{"type", "dielectric"}, {"ior", eta}}};
  }
  if (type == "interface" || type.empty()) return {"interface", Json{{"type", "null"}}};
  fail_at(where, "Material " + quote_for_message(type) +
                     " cannot be rendered by Caligo (diffuse, dielectric, interface; coateddiffuse, conductor, "
                     "coatedconductor, thindielectric and diffusetransmission approximated)");
}

std::string Builder::material_for(const MaterialSpec& spec, const GraphicsState& state, const std::string& where) {
  Json m = spec.json;
  const auto medium = media.find(state.inside);
  const bool encloses = !state.inside.empty() && medium != media.end() && medium->second.homogeneous &&
                        (m["type"] == "dielectric" || m["type"] == "null");
  if (encloses) {
    m["interior"] = state.inside;
    if (m["type"] == "null") m["ior"] = 1.0;
  }
  if (state.area_light) {
    const RGB L = state.area_light->radiance;
    if (m["type"] == "diffuse") {
      m["emission"] = to_json(L);
      m["two_sided"] = state.area_light->two_sided;
    } else {
      warnings.push_back(where + ": an area light on a " + std::string(m["type"]) +
                         " material: the shape emits but does not reflect or refract");
      m = Json{{"type", "emissive"}, {"radiance", to_json(L)}, {"two_sided", state.area_light->two_sided}};
    }
  }
  Json& materials = scene["materials"];
  for (auto it = materials.begin(); it != materials.end(); ++it)
    if (it.value() == m) return it.key();
  std::string name = "m";  // built piecewise: GCC 12 warns falsely (-Wrestrict) about "m" + std::string
  name += std::to_string(materials.size());
  materials[name] = m;
  add_origin("/materials/" + name, where);
  return name;
}

namespace {

// The area of a converted shape, for an area light's "power": spheres and inline meshes, whose
// positions are already in the world; a PLY file is not read here.
double shape_area(const Json& shape, const std::string& where) {
  if (shape["type"] == "sphere") {
    const double r = shape["radius"];
    return 4 * kPi * r * r;
  }
  if (!shape.contains("positions"))
    fail_at(where, "AreaLightSource \"diffuse\": \"power\" on a plymesh is not supported (the file is not read "
                   "while importing); give \"L\" and \"scale\"");
  const Json& p = shape["positions"];
  const Json& idx = shape["indices"];
  const auto at = [&](size_t i) {
    const size_t k = 3 * size_t(idx[i]);
    return Vec3(float(p[k]), float(p[k + 1]), float(p[k + 2]));
  };
  double area = 0;
  for (size_t i = 0; i + 2 < idx.size(); i += 3) area += 0.5 * double(length(cross(at(i + 1) - at(i), at(i + 2) - at(i))));
  if (!(area > 0)) fail_at(where, "AreaLightSource \"diffuse\": \"power\" on a shape of no area");
  return area;
}

}  // namespace

void add_shape(const std::string& type, const ParamList& p, const GraphicsState& state, const std::string& where,
               const std::string& base_dir, Builder& b) {
  const bool swaps = determinant3(state.ctm) < 0.0f;
  const bool flip = state.reverse_orientation != swaps;
  // An interface with no medium inside is invisible: nothing to add.
  if (state.material.pbrt_type == "interface" && !state.area_light) {
    if (!state.inside.empty()) b.place_medium(state.inside, where, false);
    const auto medium = b.media.find(state.inside);
    if (state.inside.empty() || medium == b.media.end() || !medium->second.homogeneous) {
      p.mark_all_used();  // an interface around a grid medium or nothing: the grid's own box bounds it
      return;
    }
  } else if (!state.inside.empty()) {
    b.place_medium(state.inside, where, false);
  }
  Json shape;
  if (type == "sphere") {
    const double r = p.number("radius", 1);
    if (!(r > 0)) fail_at(where, "Shape \"sphere\": radius must be > 0");
    if (p.number("zmin", -r) > -r || p.number("zmax", r) < r || p.number("phimax", 360) < 360.0)
      fail_at(where, "Shape \"sphere\": only whole spheres (no zmin, zmax or phimax)");
    float scale = 1.0f;
    if (!is_similarity(state.ctm, &scale))
      fail_at(where, "Shape \"sphere\": under a non-uniform scale (an ellipsoid), which Caligo has no shape for");
    shape = Json{{"type", "sphere"}, {"center", to_json(apply_point(state.ctm, {}))}, {"radius", r * scale}};
    if (state.reverse_orientation && state.area_light && !state.area_light->two_sided)
      b.warnings.push_back(where + ": ReverseOrientation on an emitting sphere is not honoured (it emits outwards)");
  } else if (type == "trianglemesh") {
    const std::vector<Vec3> points = read_points(p, "P", where);
    const std::vector<Vec3> normals = read_points(p, "N", where);
    if (!normals.empty() && normals.size() != points.size()) fail_at(where, "\"N\" must have one normal per point");
    const std::vector<uint32_t> indices = read_indices(p, points.size(), 3, where);
    p.numbers("uv");  // texture coordinates: nothing reads them
    shape = inline_mesh(points, indices, normals, state.ctm, flip);
  } else if (type == "bilinearmesh") {
    shape = bilinear_mesh(p, state.ctm, flip, where, b);
  } else if (type == "disk") {
    shape = disk_mesh(p, state.ctm, flip, where);
  } else if (type == "plymesh") {
    const std::string file = p.string("filename", "");
    if (file.empty()) fail_at(where, "Shape \"plymesh\": \"filename\" is required");
    const fs::path path = fs::path(file).is_absolute() ? fs::path(file) : fs::path(base_dir) / file;
    if (flip) b.warnings.push_back(where + ": Shape \"plymesh\": the winding is not reversed (ReverseOrientation or a mirroring transform)");
    Json matrix = Json::array();
    for (const auto& row : state.ctm.m)
      for (float v : row) matrix.push_back(v);
    shape = Json{{"type", "mesh"}, {"file", path.string()}, {"skip_degenerate", true},
                 {"transform", Json::array({Json{{"matrix", matrix}}})}};
  } else {
    fail_at(where, "Shape " + quote_for_message(type) +
                       " cannot be rendered by Caligo (sphere, disk, trianglemesh, bilinearmesh, plymesh)");
  }
  if (state.area_light && state.area_light->power > 0) {
    // pbrt-v4: the radiance times pi, the area and the sides emits the power.
    GraphicsState powered = state;
    const double area = shape_area(shape, where);
    powered.area_light->radiance *= float(state.area_light->power / ((state.area_light->two_sided ? 2 : 1) * kPi * area));
    shape["material"] = b.material_for(powered.material, powered, where);
  } else {
    shape["material"] = b.material_for(state.material, state, where);
  }
  Json& shapes = b.scene["shapes"];
  b.add_origin("/shapes/" + std::to_string(shapes.size()), where);
  shapes.push_back(shape);
}

}  // namespace caligo::pbrt
