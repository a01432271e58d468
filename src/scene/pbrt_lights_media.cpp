// pbrt-v4's lights and media as Caligo's JSON. Light spectra become RGB as pbrt-v4 scales them:
// an RGB as given, a blackbody at luminance 1, times "scale", times "power"'s conversion where
// one is given (pbrt's k_e: 4 pi for a point light, the cone's solid-angle term for a spot).
#include <cmath>
#include <filesystem>

#include "core/math.h"
#include "core/message_text.h"
#include "scene/pbrt_builder.h"

namespace caligo::pbrt {
namespace {

namespace fs = std::filesystem;

Json matrix_op(const Mat4& m) {
  Json values = Json::array();
  for (const auto& row : m.m)
    for (float v : row) values.push_back(v);
  return Json{{"matrix", values}};
}

void push_light(Json light, const std::string& where, Builder& b) {
  Json& lights = b.scene["lights"];
  b.add_origin("/lights/" + std::to_string(lights.size()), where);
  lights.push_back(std::move(light));
}

Json medium_coefficients(const ParamList& p, const std::string& where, Builder& b) {
  if (p.has("preset")) fail_at(where, "MakeNamedMedium: measured presets (\"preset\") are not known to Caligo; give sigma_a and sigma_s");
  const float scale = float(p.number("scale", 1));
  if (!(scale >= 0)) fail_at(where, "MakeNamedMedium: scale must be >= 0");
  const RGB sigma_a = p.spectrum("sigma_a", RGB(1.0f), b.warnings) * scale;
  const RGB sigma_s = p.spectrum("sigma_s", RGB(1.0f), b.warnings) * scale;
  const double g = p.number("g", 0);
  if (!(g > -1 && g < 1)) fail_at(where, "MakeNamedMedium: g must be in (-1, 1)");
  Json m{{"sigma_a", to_json(sigma_a)}, {"sigma_s", to_json(sigma_s)}, {"phase", Json{{"type", "hg"}, {"g", g}}}};
  return m;
}

// pbrt-v4's rgbgrid as one density grid times one sigma_a and one sigma_s colour (Caligo's grids
// hold one channel): exact when every voxel's two colours are the same multiples of a common
// pair, refused otherwise. The density is each voxel's mean extinction; `medium` gets the colours.
std::vector<double> rgb_grid_density(const ParamList& p, size_t voxels, const std::string& where, Json& medium) {
  const std::vector<double> a = p.rgb_numbers("sigma_a"), s = p.rgb_numbers("sigma_s");
  if (a.size() != 3 * voxels || s.size() != 3 * voxels)
    fail_at(where, "MakeNamedMedium \"rgbgrid\": \"rgb sigma_a\" and \"rgb sigma_s\" must both hold nx * ny * nz = " +
                       std::to_string(voxels) + " colours");
  const double scale = p.number("scale", 1);
  if (!(scale >= 0)) fail_at(where, "MakeNamedMedium: scale must be >= 0");
  std::vector<double> density(voxels);
  size_t densest = 0;
  for (size_t i = 0; i < voxels; ++i) {
    density[i] = (a[3 * i] + a[3 * i + 1] + a[3 * i + 2] + s[3 * i] + s[3 * i + 1] + s[3 * i + 2]) / 3;
    if (density[i] > density[densest]) densest = i;
  }
  const double top = density[densest];
  RGB sigma_a(0.0f), sigma_s(0.0f);
  if (top > 0) {
    sigma_a = RGB(float(a[3 * densest] / top), float(a[3 * densest + 1] / top), float(a[3 * densest + 2] / top));
    sigma_s = RGB(float(s[3 * densest] / top), float(s[3 * densest + 1] / top), float(s[3 * densest + 2] / top));
  }
  for (size_t i = 0; i < voxels; ++i)
    for (int c = 0; c < 3; ++c) {
      const bool same = std::abs(a[3 * i + size_t(c)] - density[i] * sigma_a[c]) <= 1e-4 * top &&
                        std::abs(s[3 * i + size_t(c)] - density[i] * sigma_s[c]) <= 1e-4 * top;
      if (!same)
        fail_at(where, "MakeNamedMedium \"rgbgrid\": voxel " + std::to_string(i) + "'s colours differ from the grid's "
                       "(Caligo's grids hold one density, which scales one sigma_a and one sigma_s colour)");
    }
  const double g = p.number("g", 0);
  if (!(g > -1 && g < 1)) fail_at(where, "MakeNamedMedium: g must be in (-1, 1)");
  medium = Json{{"sigma_a", to_json(sigma_a * float(scale))}, {"sigma_s", to_json(sigma_s * float(scale))},
                {"phase", Json{{"type", "hg"}, {"g", g}}}};
  return density;
}

}  // namespace

void add_light(const std::string& type, const ParamList& p, const GraphicsState& state, const std::string& where,
               const std::string& base_dir, Builder& b) {
  const float scale = float(p.number("scale", 1));
  if (type == "point") {
    const RGB I = p.spectrum("I", RGB(1.0f), b.warnings);
    const double power = p.number("power", -1);
    const double k = scale * (power > 0 ? power / (4 * kPi) : 1.0);  // double: the parser checks the range
    push_light(Json{{"type", "point"}, {"position", to_json(apply_point(state.ctm, p.point("from", {})))},
                    {"color", to_json(I)}, {"intensity", k}},
               where, b);
  } else if (type == "spot") {
    const RGB I = p.spectrum("I", RGB(1.0f), b.warnings);
    const double cone = p.number("coneangle", 30), delta = p.number("conedeltaangle", 5);
    if (!(cone > 0 && cone <= 179)) fail_at(where, "LightSource \"spot\": coneangle must be in (0, 179]");
    const double inner = std::max(0.0, cone - delta);
    const double power = p.number("power", -1);
    const double cos_start = std::cos(radians(float(inner))), cos_end = std::cos(radians(float(cone)));
    const double k_e = 2 * kPi * ((1 - cos_start) + (cos_start - cos_end) / 2);
    const double k = scale * (power > 0 ? power / k_e : 1.0);
    const Vec3 from = apply_point(state.ctm, p.point("from", {})), to = apply_point(state.ctm, p.point("to", {0, 0, 1}));
    if (!(length(to - from) > 0)) fail_at(where, "LightSource \"spot\": \"from\" and \"to\" are the same point");
    push_light(Json{{"type", "spot"}, {"position", to_json(from)}, {"look_at", to_json(to)}, {"inner_angle", inner},
                    {"outer_angle", cone}, {"color", to_json(I)}, {"intensity", k}},
               where, b);
  } else if (type == "distant") {
    const RGB L = p.spectrum("L", RGB(1.0f), b.warnings);
    const Vec3 d = apply_vector(state.ctm, p.point("to", {0, 0, 1}) - p.point("from", {}));
    if (!(length(d) > 0)) fail_at(where, "LightSource \"distant\": \"from\" and \"to\" are the same point");
    const double e = p.number("illuminance", -1);
    push_light(Json{{"type", "directional"}, {"direction", to_json(normalize(d))}, {"color", to_json(L)},
                    {"irradiance", scale * (e > 0 ? float(e) : 1.0f)}},
               where, b);
  } else if (type == "infinite") {
    if (p.has("filename")) {
      // pbrt-v4's equal-area square, in the light's frame (the CTM here), resampled at load.
      if (p.has("L")) fail_at(where, "LightSource \"infinite\": give \"L\" or \"filename\", not both");
      if (p.has("illuminance"))
        fail_at(where, "LightSource \"infinite\": \"illuminance\" with an image is not supported; give \"scale\"");
      const std::string file = p.string("filename", "");
      const fs::path path = fs::path(file).is_absolute() ? fs::path(file) : fs::path(base_dir) / file;
      push_light(Json{{"type", "environment"},
                      {"map", Json{{"file", path.string()}, {"projection", "equal_area"},
                                   {"transform", Json::array({matrix_op(state.ctm)})}}},
                      {"strength", scale}},
                 where, b);
      return;
    }
    const RGB L = p.spectrum("L", RGB(1.0f), b.warnings);
    const double e = p.number("illuminance", -1);  // of the upper hemisphere: pi L for a constant sky
    push_light(Json{{"type", "environment"}, {"color", to_json(L)},
                    {"radiance", scale * (e > 0 ? float(e / kPi) : 1.0f)}},
               where, b);
  } else {
    fail_at(where, "LightSource " + quote_for_message(type) + " cannot be rendered by Caligo (point, spot, distant, infinite)");
  }
}

AreaLight read_area_light(const std::string& type, const ParamList& p, const std::string& where, Builder& b) {
  if (type != "diffuse") fail_at(where, "AreaLightSource " + quote_for_message(type) + ": only \"diffuse\"");
  if (p.has("filename")) fail_at(where, "AreaLightSource \"diffuse\": image emission (\"filename\") is not supported");
  const RGB L = p.spectrum("L", RGB(1.0f), b.warnings) * float(p.number("scale", 1));
  const double power = p.number("power", -1);
  if (p.has("power") && !(power > 0)) fail_at(where, "AreaLightSource \"diffuse\": \"power\" must be > 0");
  return {L, p.boolean("twosided", false), where, power};
}

MediumSpec read_medium(const std::string& type, const ParamList& p, const Mat4& ctm, const std::string& where,
                       const std::string& base_dir, Builder& b) {
  MediumSpec spec;
  spec.where = where;
  if (type == "homogeneous") {
    spec.medium = medium_coefficients(p, where, b);
    const RGB Le = p.spectrum("Le", RGB(0.0f), b.warnings) * float(p.number("Lescale", 1));
    if (!Le.is_black()) spec.medium["emission"] = to_json(Le);
    return spec;
  }
  if (type == "uniformgrid" || type == "rgbgrid") {
    spec.homogeneous = false;
    const int nx = p.integer("nx", 1), ny = p.integer("ny", 1), nz = p.integer("nz", 1);
    if (nx < 1 || ny < 1 || nz < 1 || nx > 4096 || ny > 4096 || nz > 4096)
      fail_at(where, "MakeNamedMedium " + quote_for_message(type) + ": nx, ny and nz must be in [1, 4096]");
    const size_t voxels = size_t(nx) * size_t(ny) * size_t(nz);
    std::vector<double> density;
    if (type == "uniformgrid") {
      spec.medium = medium_coefficients(p, where, b);
      density = p.numbers("density");
    } else {
      density = rgb_grid_density(p, voxels, where, spec.medium);
    }
    if (density.size() != voxels)
      fail_at(where, "MakeNamedMedium " + quote_for_message(type) + ": \"density\" has " + std::to_string(density.size()) +
                         " values, nx * ny * nz is " + std::to_string(voxels));
    if (p.has("Le") || p.has("temperature"))
      fail_at(where, "MakeNamedMedium " + quote_for_message(type) + ": emission is not supported");
    const Vec3 p0 = p.point("p0", {}), p1 = p.point("p1", {1, 1, 1});
    if (!(p1.x > p0.x && p1.y > p0.y && p1.z > p0.z))
      fail_at(where, "MakeNamedMedium " + quote_for_message(type) + ": p1 must exceed p0");
    // Voxel (i, j, k) of unit size at the origin, then onto [p0, p1] (cell-centred, as pbrt samples), then the CTM.
    const Vec3 extent = p1 - p0;
    const Mat4 to_box = (Transform::translate(p0) *
                         Transform::scale({extent.x / float(nx), extent.y / float(ny), extent.z / float(nz)}))
                            .matrix();
    Json values = Json::array();
    for (double v : density) values.push_back(float(std::max(0.0, v)));
    spec.volume = Json{{"type", "dense"}, {"values", values}, {"dimensions", {nx, ny, nz}}, {"voxel_size", 1},
                       {"origin", {0, 0, 0}},
                       {"clip", Json{{"min", {0, 0, 0}}, {"max", {nx, ny, nz}}}}, {"transform", Json::array({matrix_op(ctm * to_box)})}};
    return spec;
  }
  if (type == "nanovdb") {
    spec.homogeneous = false;
    spec.medium = medium_coefficients(p, where, b);
    const std::string file = p.string("filename", "");
    if (file.empty()) fail_at(where, "MakeNamedMedium \"nanovdb\": \"filename\" is required");
    if (p.has("Lescale") && p.number("Lescale", 0) > 0)
      b.warnings.push_back(where + ": MakeNamedMedium \"nanovdb\": emission from the temperature grid is not imported");
    const fs::path path = fs::path(file).is_absolute() ? fs::path(file) : fs::path(base_dir) / file;
    spec.volume = Json{{"type", "vdb"}, {"file", path.string()}, {"grids", Json{{"density", "density"}}},
                       {"transform", Json::array({matrix_op(ctm)})}};
    return spec;
  }
  fail_at(where, "MakeNamedMedium " + quote_for_message(type) +
                     " cannot be rendered by Caligo (homogeneous, uniformgrid, rgbgrid, nanovdb)");
}

void Builder::place_medium(const std::string& name, const std::string& where, bool around_camera) {
  const auto it = media.find(name);
  if (it == media.end()) fail_at(where, "medium " + quote_for_message(name) + " is not defined (MakeNamedMedium)");
  MediumSpec& spec = it->second;
  if (!scene["media"].contains(name)) {
    scene["media"][name] = spec.medium;
    add_origin("/media/" + name, spec.where);
  }
  if (spec.placed || (spec.homogeneous && !around_camera)) return;
  spec.placed = true;
  Json volume = spec.homogeneous
                    // pbrt's camera medium fills all space outside the shapes: a box far larger than any scene.
                    ? Json{{"type", "box"}, {"min", {-5e4, -5e4, -5e4}}, {"max", {5e4, 5e4, 5e4}}}
                    : *spec.volume;
  volume["medium"] = name;
  Json& volumes = scene["volumes"];
  add_origin("/volumes/" + std::to_string(volumes.size()), spec.where);
  volumes.push_back(volume);
}

}  // namespace caligo::pbrt
