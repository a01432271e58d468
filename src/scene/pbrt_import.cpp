// The pbrt-v4 directive reader: the graphics state (transform, material, area light, media,
// attribute stack), the camera and render options, and the dispatch of world directives to
// pbrt_world.cpp and pbrt_lights_media.cpp.
#include "scene/pbrt_import.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>

#include "core/math.h"
#include "core/message_text.h"
#include "scene/pbrt_builder.h"
#include "scene/pbrt_instances.h"
#include "scene/scene_parser.h"

namespace caligo {
namespace pbrt {

Vec3 apply_point(const Mat4& m, Vec3 p) {
  const auto& a = m.m;
  return {a[0][0] * p.x + a[0][1] * p.y + a[0][2] * p.z + a[0][3], a[1][0] * p.x + a[1][1] * p.y + a[1][2] * p.z + a[1][3],
          a[2][0] * p.x + a[2][1] * p.y + a[2][2] * p.z + a[2][3]};
}

Vec3 apply_vector(const Mat4& m, Vec3 v) {
  const auto& a = m.m;
  return {a[0][0] * v.x + a[0][1] * v.y + a[0][2] * v.z, a[1][0] * v.x + a[1][1] * v.y + a[1][2] * v.z,
          a[2][0] * v.x + a[2][1] * v.y + a[2][2] * v.z};
}

float determinant3(const Mat4& m) {
  const auto& a = m.m;
  return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
         a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
}

namespace {

namespace fs = std::filesystem;

struct CameraState {
  std::string type = "perspective", where;
  Mat4 world_from_camera = Mat4::identity();
  double fov = 90, lens_radius = 0, focal_distance = 1e6;
  double screen_width = 0, screen_aspect = 0;
  // The LookAt's own points when it is the whole camera transform: written as given (exact).
  std::optional<std::array<Vec3, 3>> look_at;  // orthographic "screenwindow" (0: pbrt's default)
  bool given = false;
};

class Importer {
 public:
  Importer(const TokenStream& s, std::string base_dir) : s_(s), base_dir_(std::move(base_dir)) {}

  PbrtConversion run() {
    b_.scene["render"] = Json{{"spp", 16}, {"max_bounces", 5}, {"max_volume_bounces", 5},
                              {"filter", Json{{"type", "gaussian"}, {"radius", 1.5}, {"sigma", 0.5}}}};
    for (const char* key : {"materials", "media"}) b_.scene[key] = Json::object();
    for (const char* key : {"shapes", "lights", "volumes"}) b_.scene[key] = Json::array();
    while (at_ < s_.tokens.size()) directive();
    if (!world_) fail_at(s_.files[0], "no WorldBegin: the file describes no scene");
    if (instancing_.defining()) fail_at(s_.files[0], "an ObjectBegin is never closed by ObjectEnd");
    finish_camera_medium();
    for (const char* key : {"materials", "media", "shapes", "lights", "volumes"})
      if (b_.scene[key].empty()) b_.scene.erase(key);
    // The tokenizer refuses strings that are not UTF-8; replacing rather than throwing is the
    // safety net should one reach the JSON some other way.
    return {b_.scene.dump(-1, ' ', false, Json::error_handler_t::replace), std::move(b_.warnings), std::move(b_.origins)};
  }

 private:
  const Token& next(const std::string& what) {
    if (at_ >= s_.tokens.size()) fail_at(s_.where(s_.tokens.back()), "the file ends where " + what + " was expected");
    return s_.tokens[at_++];
  }
  std::string quoted(const std::string& directive) {
    const Token& t = next(directive + "'s quoted argument");
    if (t.kind != Token::kString) fail_at(s_.where(t), directive + ": expected a quoted argument, got " + quote_for_message(t.text));
    return t.text;
  }
  // `n` numbers, bare or in brackets (Transform [ ... ]).
  std::vector<float> numbers(size_t n, const std::string& directive) {
    std::vector<float> out;
    const bool bracket = at_ < s_.tokens.size() && s_.tokens[at_].kind == Token::kOpen;
    if (bracket) ++at_;
    while (out.size() < n) {
      const Token& t = next(directive + "'s numbers");
      if (t.kind != Token::kNumber) fail_at(s_.where(t), directive + ": expected " + std::to_string(n) + " numbers");
      const double d = std::strtod(t.text.c_str(), nullptr);
      const float v = std::abs(d) <= 3.0e38 ? float(d) : 0.0f;
      if (!(std::abs(d) <= 3.0e38)) fail_at(s_.where(t), directive + ": a number is not finite");
      out.push_back(v);
    }
    if (bracket && next("\"]\"").kind != Token::kClose) fail_at(s_.where(s_.tokens[at_ - 1]), directive + ": expected \"]\"");
    return out;
  }
  ParamList params() { return ParamList::read(s_, &at_); }

  void concat(const Mat4& m) { gs_.ctm = gs_.ctm * m; }
  void require_world(const std::string& directive, const std::string& where) const {
    if (!world_) fail_at(where, directive + " must come after WorldBegin");
  }

  void directive();
  void transform_directive(const std::string& name, const std::string& where);
  void option_directive(const std::string& name, const std::string& where);
  void world_directive(const std::string& name, const std::string& where);
  void camera(const std::string& where);
  void film(const std::string& type, const ParamList& p, const std::string& where);
  void world_begin(const std::string& where);
  void finish_camera_medium();
  void object_directive(const std::string& name, const std::string& where);

  const TokenStream& s_;
  std::string base_dir_;
  size_t at_ = 0;
  Builder b_;
  GraphicsState gs_;
  std::vector<GraphicsState> stack_;
  std::map<std::string, Mat4> named_coordinates_;
  CameraState camera_;
  std::string camera_medium_;
  int width_ = 1280, height_ = 720;
  std::optional<std::array<Vec3, 3>> last_look_at_;  // a LookAt on the identity, and the CTM it made
  Mat4 look_at_ctm_ = Mat4::identity();
  bool world_ = false;
  ObjectInstancing instancing_;
};

void Importer::directive() {
  const Token& t = next("a directive");
  const std::string where = s_.where(t);
  if (t.kind != Token::kWord) fail_at(where, "expected a directive, got " + quote_for_message(t.text));
  const std::string& name = t.text;
  static const std::vector<std::string> kTransforms = {"Identity", "Translate", "Scale", "Rotate", "LookAt",
                                                       "Transform", "ConcatTransform", "CoordinateSystem",
                                                       "CoordSysTransform", "TransformBegin", "TransformEnd",
                                                       "ActiveTransform", "TransformTimes", "ReverseOrientation"};
  if (std::find(kTransforms.begin(), kTransforms.end(), name) != kTransforms.end()) return transform_directive(name, where);
  if (name == "Camera" || name == "Film" || name == "Sampler" || name == "Integrator" || name == "PixelFilter" ||
      name == "Accelerator" || name == "ColorSpace" || name == "Option" || name == "WorldBegin" || name == "WorldEnd")
    return option_directive(name, where);
  if (name == "MakeNamedMedium") {
    const std::string medium = quoted(name);
    ParamList p = params();
    const std::string type = p.string("type", "");
    b_.media[medium] = read_medium(type, p, gs_.ctm, where, base_dir_, b_);
    p.warn_unused("MakeNamedMedium \"" + type + "\"", b_.warnings);
    return;
  }
  if (name == "MediumInterface") {
    gs_.inside = quoted(name);
    gs_.outside = at_ < s_.tokens.size() && s_.tokens[at_].kind == Token::kString ? quoted(name) : gs_.inside;
    for (const std::string& m : {gs_.inside, gs_.outside})
      if (!m.empty() && !b_.media.count(m)) fail_at(where, "MediumInterface: medium " + quote_for_message(m) + " is not defined");
    return;
  }
  world_directive(name, where);
}

void Importer::transform_directive(const std::string& name, const std::string& where) {
  if (name == "Identity") {
    gs_.ctm = Mat4::identity();
  } else if (name == "Translate") {
    const auto v = numbers(3, name);
    concat(Transform::translate({v[0], v[1], v[2]}).matrix());
  } else if (name == "Scale") {
    const auto v = numbers(3, name);
    if (v[0] == 0 || v[1] == 0 || v[2] == 0) fail_at(where, "Scale: a zero factor flattens everything after it");
    concat(Transform::scale({v[0], v[1], v[2]}).matrix());
  } else if (name == "Rotate") {
    const auto v = numbers(4, name);
    const Vec3 axis{v[1], v[2], v[3]};
    if (!(length(axis) > 0)) fail_at(where, "Rotate: the axis is zero");
    concat(Transform::rotate(radians(v[0]), normalize(axis)).matrix());
  } else if (name == "LookAt") {
    const auto v = numbers(9, name);
    const Vec3 eye{v[0], v[1], v[2]}, look{v[3], v[4], v[5]}, up{v[6], v[7], v[8]};
    const Vec3 dir = look - eye;
    if (!(length(dir) > 0) || !(length(cross(normalize(up), normalize(dir))) > 1e-6f))
      fail_at(where, "LookAt: the eye and the target coincide, or up is parallel to the view");
    // pbrt's camera frame: x = up x dir (left-handed), y = dir x x, z = dir.
    const Vec3 z = normalize(dir), x = normalize(cross(normalize(up), z)), y = cross(z, x);
    Mat4 world_from_camera = Mat4::identity();
    for (int r = 0; r < 3; ++r) {
      world_from_camera.m[r][0] = x[r];
      world_from_camera.m[r][1] = y[r];
      world_from_camera.m[r][2] = z[r];
      world_from_camera.m[r][3] = eye[r];
    }
    const bool alone = gs_.ctm == Mat4::identity();
    concat(*world_from_camera.inverse());
    if (alone) last_look_at_ = std::array<Vec3, 3>{eye, look, up};
    look_at_ctm_ = gs_.ctm;
  } else if (name == "Transform" || name == "ConcatTransform") {
    const auto v = numbers(16, name);
    Mat4 m;
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) m.m[r][c] = v[size_t(c * 4 + r)];  // pbrt lists the matrix column by column
    if (!m.inverse()) fail_at(where, name + ": the matrix is singular");
    if (name == "Transform") gs_.ctm = m; else concat(m);
  } else if (name == "CoordinateSystem") {
    named_coordinates_[quoted(name)] = gs_.ctm;
  } else if (name == "CoordSysTransform") {
    const std::string system = quoted(name);
    const auto it = named_coordinates_.find(system);
    if (it == named_coordinates_.end()) fail_at(where, "CoordSysTransform: no coordinate system " + quote_for_message(system));
    gs_.ctm = it->second;
  } else if (name == "TransformBegin") {
    stack_.push_back(gs_);
    stack_.back().material.pbrt_type = "<transform>";  // marks a transform-only push
  } else if (name == "TransformEnd") {
    if (stack_.empty() || stack_.back().material.pbrt_type != "<transform>") fail_at(where, "TransformEnd without TransformBegin");
    gs_.ctm = stack_.back().ctm;
    stack_.pop_back();
  } else if (name == "ReverseOrientation") {
    gs_.reverse_orientation = !gs_.reverse_orientation;
  } else if (name == "ActiveTransform") {
    next("ActiveTransform's argument");
    b_.warnings.push_back(where + ": ActiveTransform: motion blur is not rendered; every transform applies at time 0");
  } else {  // TransformTimes
    numbers(2, name);
    b_.warnings.push_back(where + ": TransformTimes: motion blur is not rendered");
  }
}

void Importer::option_directive(const std::string& name, const std::string& where) {
  if (name == "WorldBegin") return world_begin(where);
  if (name == "WorldEnd") return;  // pbrt-v3's; the file's end ends the world
  if (world_) fail_at(where, name + " must come before WorldBegin");
  if (name == "Camera") return camera(where);
  if (name == "ColorSpace") {
    const std::string space = quoted(name);
    if (space != "srgb") b_.warnings.push_back(where + ": ColorSpace " + quote_for_message(space) + ": colours are read as sRGB (Rec.709) primaries");
    return;
  }
  if (name == "Option") {
    ParamList p = params();
    p.warn_unused("Option", b_.warnings);
    return;
  }
  const std::string type = quoted(name);
  ParamList p = params();
  Json& render = b_.scene["render"];
  if (name == "Film") {
    film(type, p, where);
  } else if (name == "Sampler") {
    const int spp = p.integer("pixelsamples", 16);
    if (spp < 1 || spp > 1000000) fail_at(where, "Sampler: pixelsamples must be in [1, 1000000]");
    render["spp"] = spp;
    p.warn_unused("Sampler \"" + type + "\"", b_.warnings);
    return;  // the sampler's kind is not a property of the image
  } else if (name == "Integrator") {
    if (type != "volpath" && type != "path")
      b_.warnings.push_back(where + ": Integrator " + quote_for_message(type) + ": rendered with Caligo's volumetric path tracer");
    const int depth = p.integer("maxdepth", 5);
    if (depth < 0 || depth > 10000) fail_at(where, "Integrator: maxdepth must be in [0, 10000]");
    render["max_bounces"] = depth;
    render["max_volume_bounces"] = depth;
  } else if (name == "PixelFilter") {
    if (type == "box") {
      render["filter"] = Json{{"type", "box"}, {"radius", p.number("xradius", 0.5)}};
      p.number("yradius", 0.5);
    } else if (type == "gaussian") {
      render["filter"] = Json{{"type", "gaussian"}, {"radius", p.number("xradius", 1.5)}, {"sigma", p.number("sigma", 0.5)}};
      p.number("yradius", 1.5);
    } else {
      b_.warnings.push_back(where + ": PixelFilter " + quote_for_message(type) + ": rendered with pbrt's default gaussian filter");
    }
  }
  if (name != "Accelerator") p.warn_unused(name + " \"" + type + "\"", b_.warnings);
}

void Importer::camera(const std::string& where) {
  camera_.type = quoted("Camera");
  camera_.where = where;
  camera_.given = true;
  ParamList p = params();
  if (camera_.type != "perspective" && camera_.type != "orthographic")
    fail_at(where, "Camera " + quote_for_message(camera_.type) + " cannot be rendered by Caligo (perspective, orthographic)");
  const std::optional<Mat4> inverse = gs_.ctm.inverse();
  if (!inverse) fail_at(where, "Camera: the transform is singular");
  camera_.world_from_camera = *inverse;
  if (last_look_at_ && gs_.ctm == look_at_ctm_) camera_.look_at = last_look_at_;
  named_coordinates_["camera"] = *inverse;
  camera_.fov = p.number("fov", 90);
  if (!(camera_.fov > 0 && camera_.fov < 180)) fail_at(where, "Camera: fov must be in (0, 180)");
  camera_.lens_radius = p.number("lensradius", 0);
  camera_.focal_distance = p.number("focaldistance", 1e6);
  if (!(camera_.lens_radius >= 0) || !(camera_.focal_distance > 0)) fail_at(where, "Camera: lensradius >= 0, focaldistance > 0");
  if (camera_.type == "orthographic" && p.has("screenwindow")) {
    const std::vector<double> w = p.numbers("screenwindow");
    if (w.size() != 4 || !(w[1] > w[0]) || !(w[3] > w[2])) fail_at(where, "Camera: screenwindow is [x0 x1 y0 y1] with x1 > x0, y1 > y0");
    if (std::abs(w[0] + w[1]) > 1e-6 * (w[1] - w[0]) || std::abs(w[2] + w[3]) > 1e-6 * (w[3] - w[2]))
      fail_at(where, "Camera: an off-centre screenwindow is not supported");
    camera_.screen_width = w[1] - w[0];
    camera_.screen_aspect = (w[1] - w[0]) / (w[3] - w[2]);
  }
  camera_medium_ = gs_.outside;
  p.warn_unused("Camera \"" + camera_.type + "\"", b_.warnings);
}

void Importer::film(const std::string& type, const ParamList& p, const std::string& where) {
  if (type != "rgb" && type != "gbuffer" && type != "spectral")
    fail_at(where, "Film " + quote_for_message(type) + ": expected rgb, gbuffer or spectral");
  width_ = p.integer("xresolution", 1280);
  height_ = p.integer("yresolution", 720);
  if (width_ < 1 || height_ < 1 || width_ > 16384 || height_ > 16384)
    fail_at(where, "Film: xresolution and yresolution must be in [1, 16384]");
  const std::string file = p.string("filename", "");
  if (!file.empty())
    b_.warnings.push_back(where + ": Film: the output is named by -o, not by \"filename\" (" + quote_for_message(file) + ")");
}

void Importer::world_begin(const std::string& where) {
  if (world_) fail_at(where, "a second WorldBegin");
  world_ = true;
  const Mat4& m = camera_.world_from_camera;
  const Vec3 eye = apply_point(m, {}), forward = normalize(apply_vector(m, {0, 0, 1})),
             up = normalize(apply_vector(m, {0, 1, 0})), right = apply_vector(m, {1, 0, 0});
  Json camera{{"position", to_json(eye)}, {"look_at", to_json(eye + forward)}, {"up", to_json(up)},
              {"resolution", {width_, height_}}};
  if (camera_.look_at) {
    camera["position"] = to_json((*camera_.look_at)[0]);
    camera["look_at"] = to_json((*camera_.look_at)[1]);
    camera["up"] = to_json((*camera_.look_at)[2]);
  }
  // Caligo's image x grows along forward x up; pbrt's along its camera x axis.
  if (dot(right, cross(forward, up)) < 0) camera["handedness"] = "left";
  const double aspect = double(width_) / double(height_);
  if (camera_.type == "orthographic") {
    camera["projection"] = "orthographic";
    camera["ortho_width"] = camera_.screen_width > 0 ? camera_.screen_width : (aspect >= 1 ? 2 * aspect : 2.0);
  } else {
    // pbrt's fov spans the image's shorter side; Caligo's is vertical.
    const double half = radians(float(camera_.fov)) / 2;
    camera["fov"] = aspect >= 1 ? camera_.fov : degrees(float(2 * std::atan(std::tan(half) / aspect)));
    if (camera_.lens_radius > 0) {
      camera["aperture_radius"] = camera_.lens_radius;
      camera["focus_distance"] = camera_.focal_distance;
    }
  }
  if (camera_.screen_aspect > 0 && std::abs(camera_.screen_aspect - aspect) > 1e-4 * aspect)
    b_.warnings.push_back(camera_.where + ": Camera: the screenwindow's aspect differs from the film's; Caligo keeps square pixels, "
                          "so the window's height follows the film");
  b_.scene["camera"] = camera;
  b_.add_origin("/camera", camera_.given ? camera_.where : where);
  gs_.ctm = Mat4::identity();
  named_coordinates_["world"] = gs_.ctm;
}

void Importer::finish_camera_medium() {
  if (camera_medium_.empty()) return;
  const MediumSpec& spec = b_.media.at(camera_medium_);
  if (spec.homogeneous)
    for (const auto& [name, m] : b_.scene["materials"].items())
      if (m.contains("interior") && m["interior"] == camera_medium_) return;  // a shape bounds it
  b_.place_medium(camera_medium_, camera_.where, true);
}

// ObjectBegin opens an attribute block, as in pbrt; ObjectEnd closes it.
void Importer::object_directive(const std::string& name, const std::string& where) {
  require_world(name, where);
  if (name == "ObjectBegin") {
    const std::string object = quoted(name);
    stack_.push_back(gs_);
    instancing_.begin(object, where, b_);
  } else if (name == "ObjectEnd") {
    instancing_.end(where, b_);
    if (stack_.empty() || stack_.back().material.pbrt_type == "<transform>") fail_at(where, "ObjectEnd without ObjectBegin");
    gs_ = stack_.back();
    stack_.pop_back();
  } else {
    instancing_.instance(quoted(name), gs_.ctm, where, b_);
  }
}

void Importer::world_directive(const std::string& name, const std::string& where) {
  if (name == "AttributeBegin") {
    stack_.push_back(gs_);
    return;
  }
  if (name == "AttributeEnd") {
    if (stack_.empty() || stack_.back().material.pbrt_type == "<transform>") fail_at(where, "AttributeEnd without AttributeBegin");
    gs_ = stack_.back();
    stack_.pop_back();
    return;
  }
  if (name == "ObjectBegin" || name == "ObjectEnd" || name == "ObjectInstance") {
    object_directive(name, where);
    return;
  }
  if (name == "NamedMaterial") {
    const std::string material = quoted(name);
    const auto it = b_.named_materials.find(material);
    if (it == b_.named_materials.end()) fail_at(where, "NamedMaterial: no material " + quote_for_message(material));
    gs_.material = it->second;
    return;
  }
  if (name == "Attribute") {
    quoted(name);
    params().warn_unused("Attribute", b_.warnings);
    return;
  }
  if (name == "Texture") {
    const std::string texture = quoted(name);
    quoted(name);
    const std::string kind = quoted(name);
    ParamList p = params();
    b_.warnings.push_back(where + ": Texture " + quote_for_message(texture) + " (" + quote_for_message(kind) +
                          "): textures are not read; materials that use it get their default values");
    return;
  }
  const bool named = name == "MakeNamedMaterial";
  if (name != "Shape" && name != "Material" && !named && name != "LightSource" && name != "AreaLightSource")
    fail_at(where, "unknown directive " + quote_for_message(name));
  const std::string first = quoted(name);
  ParamList p = params();
  const std::string type = named ? p.string("type", "") : first;
  const std::string label = name + " " + quote_for_message(type);
  if (instancing_.defining() && (name == "LightSource" || (name == "Shape" && gs_.area_light)))
    fail_at(where, label + ": lights inside an object definition (ObjectBegin) are not supported, as in pbrt-v4");
  if (name == "Shape") {
    require_world(name, where);
    add_shape(type, p, gs_, where, base_dir_, b_);
  } else if (name == "Material" || named) {
    MaterialSpec spec = read_material(type, p, where, b_);
    if (named) b_.named_materials[first] = spec; else gs_.material = spec;
  } else if (name == "LightSource") {
    require_world(name, where);
    add_light(type, p, gs_, where, base_dir_, b_);
  } else {
    gs_.area_light = read_area_light(type, p, where, b_);
  }
  p.warn_unused(label, b_.warnings);
}

PbrtConversion convert(const TokenStream& tokens, const std::string& base_dir) {
  if (tokens.tokens.empty()) fail_at(tokens.files[0], "the file holds no directives");
  return Importer(tokens, base_dir).run();
}

}  // namespace
}  // namespace pbrt

bool is_pbrt_path(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext == ".pbrt";
}

PbrtConversion convert_pbrt_file(const std::string& path) {
  const std::string dir = std::filesystem::path(path).parent_path().string();
  return pbrt::convert(pbrt::tokenize_pbrt_file(path), dir);
}

PbrtConversion convert_pbrt_text(const std::string& text, const std::string& label, const std::string& base_dir) {
  return pbrt::convert(pbrt::tokenize_pbrt_text(text, label, base_dir), base_dir);
}

SceneDesc parse_pbrt(const PbrtConversion& conversion, const std::string& label, const std::string& base_dir) {
  try {
    SceneDesc desc = parse_scene_text(conversion.json, label, base_dir);
    desc.warnings.insert(desc.warnings.begin(), conversion.warnings.begin(), conversion.warnings.end());
    return desc;
  } catch (const InputError& e) {
    // Reported at the directive the offending JSON came from (the longest matching pointer).
    const std::string& pointer = e.where().json_path;
    const std::pair<std::string, std::string>* best = nullptr;
    for (const auto& origin : conversion.origins)
      if ((pointer == origin.first || pointer.rfind(origin.first + "/", 0) == 0) &&
          (!best || origin.first.size() > best->first.size()))
        best = &origin;
    if (!best) throw;
    std::string what = e.what();
    const std::string prefix = e.where().to_string() + ": ";
    if (what.rfind(prefix, 0) == 0) what = what.substr(prefix.size());
    throw InputError(SourceLocation{best->second, ""}, what + " (the converted scene's " + pointer + ")");
  }
}

SceneDesc parse_pbrt_file(const std::string& path) {
  return parse_pbrt(convert_pbrt_file(path), path, std::filesystem::path(path).parent_path().string());
}

}  // namespace caligo
