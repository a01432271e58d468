#include "scene/light_parser.h"

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/math.h"
#include "image/image_read.h"
#include "lights/environment_map.h"
#include "lights/equal_area.h"
#include "lights/gobo.h"
#include "lights/gobo_generate.h"
#include "lights/ies.h"
#include "lights/light_profile.h"
#include "lights/sky_generate.h"
#include "scene/shared_readers.h"
#include "scene/transform_parser.h"

namespace caligo {
namespace {

constexpr double kMaxAngle = 179;         // spot cone half-angles, degrees
constexpr double kMaxAngularRadius = 45;  // directional light, degrees
constexpr double kMinShadowMap = 16, kMaxShadowMap = 8192;

// ---- emission ----

// color x (the direct quantity, or "power" converted with `per_watt`).
RGB read_emission(ObjectReader& r, std::string_view direct_key, float per_watt) {
  const RGB color = r.rgb_or("color", RGB(1.0f));
  const auto [which, c] = r.exactly_one(direct_key, "power");
  const RGB amount = c.rgb();
  return color * (which == 0 ? amount : amount * per_watt);
}

// The solid angle a spot's cone times its IES profile covers: P = I * this. Integrated
// numerically (midpoint rule in cos theta and phi around the axis), since a profile need
// not be symmetric about the spot's axis in a way a formula could use.
float spot_profile_solid_angle(const SpotLight& l) {
  constexpr int kCos = 512, kPhi = 64;
  const Frame frame = Frame::from_z(l.direction);
  const float lo = std::max(-1.0f, l.cos_outer);
  double sum = 0.0;
  for (int i = 0; i < kCos; ++i) {
    const float cos_t = lo + (1.0f - lo) * (i + 0.5f) / kCos;
    const float sin_t = safe_sqrt(1.0f - cos_t * cos_t);
    for (int j = 0; j < kPhi; ++j) {
      const Vec3 w = frame.to_world(spherical_direction(sin_t, cos_t, 2.0f * kPi * (j + 0.5f) / kPhi));
      sum += spot_cone(l, w) * ies_factor(l.ies, w);
    }
  }
  return float(sum * (1.0f - lo) * 2.0 * kPi / (double(kCos) * kPhi));
}

// ---- attached files ----

std::shared_ptr<const GoboImage> load_gobo_image(const JsonCursor& c, LightFileCache& files) {
  const std::string path = files.files.resolve(c);
  if (auto it = files.gobos.find(path); it != files.gobos.end()) return it->second;
  try {
    const Image image = read_image_rgb(path);
    std::vector<RGB> pixels(image.pixel_count());
    for (size_t p = 0; p < pixels.size(); ++p)
      pixels[p] = {image.pixels()[3 * p], image.pixels()[3 * p + 1], image.pixels()[3 * p + 2]};
    auto gobo = std::make_shared<const GoboImage>(image.width(), image.height(), std::move(pixels));
    files.gobos.emplace(path, gobo);
    return gobo;
  } catch (const InputError& e) {
    c.fail(std::string("cannot use the gobo image: ") + e.what());
  }
}

std::shared_ptr<const IesProfile> load_profile(const JsonCursor& c, LightFileCache& files) {
  const std::string path = files.files.resolve(c);
  if (auto it = files.profiles.find(path); it != files.profiles.end()) return it->second;
  try {
    auto profile = std::make_shared<const IesProfile>(IesProfile::load(path));
    files.profiles.emplace(path, profile);
    return profile;
  } catch (const InputError& e) {
    c.fail(std::string("cannot use the IES profile: ") + e.what());
  }
}

// Whether the linear part of `t` is a rotation (orthonormal, not mirrored) within float error;
// a translation does not move directions and is ignored.
bool is_rotation(const Transform& t) {
  const auto& m = t.matrix().m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      float dot_ij = 0.0f;
      for (int k = 0; k < 3; ++k) dot_ij += m[size_t(k)][size_t(i)] * m[size_t(k)][size_t(j)];
      if (std::abs(dot_ij - (i == j ? 1.0f : 0.0f)) > 1e-4f) return false;
    }
  return !t.swaps_handedness();
}

// pbrt-v4's equal-area square (lights/equal_area.h), turned into the world by `to_world` and
// resampled to a lat-long map at load.
struct EqualArea {
  Transform to_world;
};

// A lat-long (or equal-area) image file, read once per scene and projection. Negative pixel
// values were clamped to 0 by read_image_rgb; non-finite ones are rejected there.
std::shared_ptr<const EnvironmentMap> load_environment_map(const JsonCursor& c, LightFileCache& files,
                                                           const std::optional<EqualArea>& equal_area = std::nullopt) {
  const std::string path = files.files.resolve(c);
  std::string key = path;
  if (equal_area)
    for (const auto& row : equal_area->to_world.matrix().m)
      for (float v : row) key.append(" ").append(std::to_string(v));
  if (auto it = files.environment_maps.find(key); it != files.environment_maps.end()) return it->second;
  try {
    const Image image = read_image_rgb(path);
    std::vector<RGB> pixels(image.pixel_count());
    for (size_t p = 0; p < pixels.size(); ++p)
      pixels[p] = {image.pixels()[3 * p], image.pixels()[3 * p + 1], image.pixels()[3 * p + 2]};
    if (equal_area && image.width() != image.height())
      c.fail("an equal-area environment map is square; " + path + " is " + std::to_string(image.width()) + "x" +
             std::to_string(image.height()));
    auto map = equal_area ? std::make_shared<const EnvironmentMap>(
                                2 * image.width(), image.width(),
                                equal_area_to_latlong(pixels, image.width(), equal_area->to_world))
                          : std::make_shared<const EnvironmentMap>(image.width(), image.height(), std::move(pixels));
    files.environment_maps.emplace(key, map);
    return map;
  } catch (const InputError& e) {
    c.fail(std::string("cannot use the environment map: ") + e.what());
  } catch (const std::invalid_argument& e) {
    c.fail("cannot use the environment map " + path + ": " + e.what());
  }
}

// {"kind": "sky", "resolution", "sun_elevation", "sun_azimuth", "sun_size"}: lights/sky_generate.h.
std::shared_ptr<const EnvironmentMap> generate_environment_map(const JsonCursor& c) {
  ObjectReader r(c, "a generated environment map");
  r.allow({"kind", "resolution", "sun_elevation", "sun_azimuth", "sun_size"});
  r.choice("kind", {"sky"});
  SkyParameters p;
  p.resolution = int(r.integer_or("resolution", p.resolution, Range::closed(kMinSkyResolution, kMaxSkyResolution)));
  p.sun_elevation = r.number_or("sun_elevation", p.sun_elevation, Range::closed(0, 90));
  p.sun_azimuth = r.number_or("sun_azimuth", p.sun_azimuth);
  p.sun_angular_radius = r.number_or("sun_size", p.sun_angular_radius, Range::closed(0.05, 10));
  r.finish();
  return std::make_shared<const EnvironmentMap>(generate_sky(p));
}

// "map": "file.exr", {"file": "file.exr"} or {"generate": {...}}; a file may be pbrt-v4's
// equal-area square ("projection": "equal_area", turned by "transform", a rotation).
std::shared_ptr<const EnvironmentMap> read_environment_map(const JsonCursor& c, LightFileCache& files) {
  if (c.is_string()) return load_environment_map(c, files);
  ObjectReader r(c, "an environment map (a file name, {\"file\": ...} or {\"generate\": ...})");
  r.allow({"file", "generate", "projection", "transform"});
  const auto [which, m] = r.exactly_one("file", "generate");
  std::optional<EqualArea> equal_area;
  if (r.has("projection") && r.choice("projection", {"latlong", "equal_area"}) == "equal_area") {
    if (which != 0) r.required("projection").fail("\"equal_area\" is a projection of an image file");
    equal_area = EqualArea{};
    if (auto t = r.optional("transform")) {
      equal_area->to_world = parse_transform(*t);
      if (!is_rotation(equal_area->to_world)) t->fail("an environment map's transform must be a rotation");
    }
  } else if (r.has("transform")) {
    r.required("transform").fail("\"transform\" turns an equal-area map; a lat-long map takes the light's \"rotation\"");
  }
  auto map = which == 0 ? load_environment_map(m, files, equal_area) : generate_environment_map(m);
  r.finish();
  return map;
}

// "generate": {"kind", "resolution", "seed"}: a procedural image (lights/gobo_generate.h).
std::shared_ptr<const GoboImage> generate_gobo_image(const JsonCursor& c) {
  ObjectReader r(c, "a generated gobo");
  r.allow({"kind", "resolution", "seed"});
  const std::string kind = r.choice("kind", {"stained_glass", "bars", "checker"});
  const int res = int(r.integer_or("resolution", 256, Range::closed(kMinGoboResolution, kMaxGoboResolution)));
  const auto seed = uint32_t(r.integer_or("seed", 1, Range::closed(0, UINT32_MAX)));
  r.finish();
  return std::make_shared<const GoboImage>(generate_gobo(*parse_gobo_pattern(kind), res, seed));
}

Gobo read_gobo(const JsonCursor& c, LightFileCache& files) {
  ObjectReader r(c, "a gobo");
  r.allow({"file", "generate", "offset", "rotation", "scroll", "spin"});
  Gobo gobo;
  const auto [which, image] = r.exactly_one("file", "generate");
  gobo.image = which == 0 ? load_gobo_image(image, files) : generate_gobo_image(image);
  if (auto o = r.optional("offset")) gobo.offset = read_vec2(*o);
  gobo.rotation = radians(r.number_or("rotation", 0.0f));
  if (auto s = r.optional("scroll")) gobo.scroll = read_vec2(*s);
  gobo.spin = radians(r.number_or("spin", 0.0f));
  r.finish();
  return gobo;
}

// `fixed_axis`: the spot's direction (a spot's profile is aimed by the spot itself).
IesAttachment read_ies(const JsonCursor& c, LightFileCache& files, const Vec3* fixed_axis) {
  ObjectReader r(c, "an IES profile");
  if (fixed_axis)
    r.allow({"file"});
  else
    r.allow({"file", "axis"});
  IesAttachment ies;
  ies.profile = load_profile(r.required("file"), files);
  if (fixed_axis)
    ies.axis = *fixed_axis;
  else if (auto a = r.optional("axis"))
    ies.axis = read_direction(*a);
  r.finish();
  return ies;
}

// ---- orientation ----

Vec3 read_aim(ObjectReader& r, Vec3 position) {
  const auto [which, aim] = r.exactly_one("look_at", "direction");
  return which == 0 ? read_target_direction(aim, position, "position") : read_direction(aim);
}

// "up", made perpendicular to `direction`. Without one: world +y, or -z when the light
// points straight up or down.
Vec3 read_up(ObjectReader& r, Vec3 direction) {
  Vec3 up{0.0f, 1.0f, 0.0f};
  if (auto c = r.optional("up")) {
    up = read_direction(*c);
    if (parallel(up, direction))
      c->fail("expected an up vector not parallel to the direction " + format_vec3(direction) + ", got " +
              c->describe());
  } else if (parallel(up, direction)) {
    up = {0.0f, 0.0f, -1.0f};
  }
  return normalize(up - direction * dot(up, direction));
}

float read_range(ObjectReader& r, float fallback) { return r.number_or("range", fallback, size_range()); }

// ---- options and animation ----

struct Movable {
  bool position = false, direction = false;
};

std::vector<LightKey> read_keys(const JsonCursor& c, Movable can, Vec3 light_position) {
  std::vector<LightKey> keys;
  const auto elements = c.elements("an array of keys");
  if (elements.empty()) c.fail("expected at least one key, got an empty array");
  for (const JsonCursor& e : elements) {
    ObjectReader r(e, "a light key");
    if (can.position && can.direction)
      r.allow({"time", "position", "direction", "look_at"});
    else if (can.position)
      r.allow({"time", "position"});
    else
      r.allow({"time", "direction"});
    LightKey k;
    k.time = read_key_time(r, keys.empty() ? nullptr : &keys.back().time);
    if (can.position) k.position = r.optional_vec3("position");
    if (can.direction && can.position && (r.has("direction") || r.has("look_at")))
      k.direction = read_aim(r, k.position.value_or(light_position));
    else if (can.direction && r.has("direction"))
      k.direction = read_direction(r.required("direction"));
    if (!k.position && !k.direction)
      r.fail(std::string("expected a key to give ") + (can.position ? "a position" : "") +
             (can.position && can.direction ? " or " : "") + (can.direction ? "a direction" : ""));
    r.finish();
    keys.push_back(k);
  }
  return keys;
}

LightOptions read_options(ObjectReader& r, std::optional<Movable> movable, Vec3 light_position) {
  LightOptions o;
  if (auto v = r.optional("volumetric")) {
    if (v->is_object()) {
      ObjectReader vr(*v, "the volumetric settings");
      vr.allow({"enabled", "intensity"});
      o.volumetric = vr.boolean_or("enabled", true);
      o.volumetric_intensity = vr.number_or("intensity", 1.0f, Range::non_negative());
      vr.finish();
    } else {
      o.volumetric = v->boolean();
    }
  }
  o.shadow = r.boolean_or("shadow", o.shadow);
  o.shadow_map_size =
      int(r.integer_or("shadow_map_size", o.shadow_map_size, Range::closed(kMinShadowMap, kMaxShadowMap)));
  if (movable) {
    if (auto a = r.optional("animation")) {
      ObjectReader ar(*a, "a light animation");
      ar.allow({"interpolation", "keys"});
      o.interpolation = read_interpolation(ar);
      o.animation = read_keys(ar.required("keys"), *movable, light_position);
      ar.finish();
    }
  }
  return o;
}

// ---- the light types ----

ParsedLight read_point(ObjectReader& r, LightFileCache& files) {
  r.allow({"type", "position", "color", "intensity", "power", "range", "ies", "volumetric", "shadow",
           "shadow_map_size", "animation"});
  PointLight light;
  light.position = r.vec3("position");
  light.range = read_range(r, kInfinity);
  if (auto c = r.optional("ies")) light.ies = read_ies(*c, files, nullptr);
  // P = 4 pi I mean(profile): the profile's peak is I.
  const float mean = light.ies.profile ? light.ies.profile->mean() : 1.0f;
  light.intensity = read_emission(r, "intensity", kInv4Pi / mean);
  return {light, read_options(r, Movable{true, false}, light.position)};
}

ParsedLight read_spot(ObjectReader& r, LightFileCache& files) {
  r.allow({"type", "position", "look_at", "direction", "inner_angle", "outer_angle", "color", "intensity",
           "power", "range", "up", "gobo", "ies", "volumetric", "shadow", "shadow_map_size", "animation"});
  SpotLight light;
  light.position = r.vec3("position");
  light.direction = read_aim(r, light.position);
  const JsonCursor inner_c = r.required("inner_angle");
  const float inner = inner_c.number(Range::closed(0, kMaxAngle));
  const float outer = r.number("outer_angle", Range::above_up_to(0, kMaxAngle));
  if (inner > outer)
    inner_c.fail("expected inner_angle <= outer_angle (" + format_number(outer) + "), got " +
                 inner_c.describe());
  light.cos_inner = std::cos(radians(inner));
  light.cos_outer = std::cos(radians(outer));
  light.range = read_range(r, kInfinity);
  light.up = read_up(r, light.direction);
  if (auto c = r.optional("gobo")) light.gobo = read_gobo(*c, files);
  if (auto c = r.optional("ies")) light.ies = read_ies(*c, files, &light.direction);
  // Power of the smoothstep cone (as in pbrt-v4): P = 2 pi I (1 - (cos_inner + cos_outer) / 2),
  // or the cone times the profile, integrated. The gobo filters the light after this.
  const float solid_angle = light.ies.profile
                                ? spot_profile_solid_angle(light)
                                : 2.0f * kPi * (1.0f - 0.5f * (light.cos_inner + light.cos_outer));
  if (!(solid_angle > 0.0f) && r.has("power"))
    r.required("ies").fail("the IES profile emits nothing inside the cone, so \"power\" cannot be met");
  light.intensity = read_emission(r, "intensity", 1.0f / solid_angle);
  return {light, read_options(r, Movable{true, true}, light.position)};
}

ParsedLight read_box(ObjectReader& r, LightFileCache& files) {
  r.allow({"type", "position", "look_at", "direction", "up", "width", "height", "range", "color",
           "irradiance", "power", "gobo", "volumetric", "shadow", "shadow_map_size", "animation"});
  BoxLight light;
  light.position = r.vec3("position");
  light.direction = read_aim(r, light.position);
  light.up = read_up(r, light.direction);
  const float width = r.number("width", size_range()), height = r.number("height", size_range());
  light.half_width = 0.5f * width;
  light.half_height = 0.5f * height;
  light.range = read_range(r, light.range);
  if (auto c = r.optional("gobo")) light.gobo = read_gobo(*c, files);
  light.irradiance = read_emission(r, "irradiance", 1.0f / (width * height));  // P = E w h
  return {light, read_options(r, Movable{true, true}, light.position)};
}

ParsedLight read_sphere_light(ObjectReader& r) {
  r.allow({"type", "center", "radius", "two_sided", "color", "radiance", "power", "volumetric", "shadow",
           "shadow_map_size"});
  SphereLight light;
  light.center = r.vec3("center");
  light.radius = r.number("radius", size_range());
  light.two_sided = r.boolean_or("two_sided", false);
  const float area = 4.0f * kPi * sqr(light.radius);
  const float sides = light.two_sided ? 2.0f : 1.0f;
  light.radiance = read_emission(r, "radiance", 1.0f / (sides * kPi * area));  // P = pi L A per side
  return {light, read_options(r, std::nullopt, {})};
}

ParsedLight read_quad(ObjectReader& r) {
  r.allow({"type", "corner", "edge1", "edge2", "two_sided", "color", "radiance", "power", "volumetric",
           "shadow", "shadow_map_size"});
  QuadLight light;
  read_parallelogram(r, light.corner, light.edge1, light.edge2);
  light.two_sided = r.boolean_or("two_sided", false);
  const float area = length(cross(light.edge1, light.edge2));
  const float sides = light.two_sided ? 2.0f : 1.0f;
  light.radiance = read_emission(r, "radiance", 1.0f / (sides * kPi * area));  // P = pi L A per side
  return {light, read_options(r, std::nullopt, {})};
}

ParsedLight read_disk(ObjectReader& r) {
  r.allow({"type", "center", "normal", "radius", "two_sided", "color", "radiance", "power", "volumetric", "shadow",
           "shadow_map_size"});
  DiskLight light;
  light.center = r.vec3("center");
  light.normal = read_direction(r.required("normal"));
  light.radius = r.number("radius", size_range());
  light.two_sided = r.boolean_or("two_sided", false);
  const float sides = light.two_sided ? 2.0f : 1.0f;
  light.radiance = read_emission(r, "radiance", 1.0f / (sides * kPi * light.area()));  // P = pi L A per side
  return {light, read_options(r, std::nullopt, {})};
}

ParsedLight read_directional(ObjectReader& r) {
  r.allow({"type", "direction", "color", "irradiance", "angular_radius", "volumetric", "shadow",
           "shadow_map_size", "animation"});
  DirectionalLight light;
  light.direction = read_direction(r.required("direction"));
  const RGB color = r.rgb_or("color", RGB(1.0f));
  light.irradiance = color * r.rgb("irradiance");
  const float angular_radius = r.number_or("angular_radius", 0.0f, Range::closed(0, kMaxAngularRadius));
  light.cos_angular_radius = std::cos(radians(angular_radius));
  return {light, read_options(r, Movable{false, true}, {})};
}

// "map": the image radiance comes from, times color x radiance x strength (radiance defaults
// to 1 with a map and is required without one).
ParsedLight read_environment(ObjectReader& r, LightFileCache& files) {
  r.allow({"type", "color", "radiance", "strength", "map", "rotation", "visible", "volumetric", "shadow",
           "shadow_map_size"});
  EnvironmentLight light;
  const RGB color = r.rgb_or("color", RGB(1.0f));
  const float strength = r.number_or("strength", 1.0f, Range::non_negative());
  if (auto m = r.optional("map")) {
    light.map = read_environment_map(*m, files);
    light.radiance = color * r.rgb_or("radiance", RGB(1.0f)) * strength;
    const float rotation = radians(r.number_or("rotation", 0.0f));
    light.cos_rotation = std::cos(rotation);
    light.sin_rotation = std::sin(rotation);
  } else {
    light.radiance = color * r.rgb("radiance") * strength;
    if (r.has("rotation"))
      r.required("rotation").fail("\"rotation\" turns an environment map, and this environment has no \"map\"");
  }
  light.visible = r.boolean_or("visible", true);
  return {light, read_options(r, std::nullopt, {})};
}

}  // namespace

ParsedLight parse_light(const JsonCursor& c, LightFileCache& files) {
  ObjectReader r(c, "a light");
  const std::string type =
      r.choice("type", {"point", "spot", "box", "sphere", "quad", "disk", "directional", "environment"});
  r.set_what("a " + type + " light");
  ParsedLight parsed;
  if (type == "point") {
    parsed = read_point(r, files);
  } else if (type == "spot") {
    parsed = read_spot(r, files);
  } else if (type == "box") {
    parsed = read_box(r, files);
  } else if (type == "sphere") {
    parsed = read_sphere_light(r);
  } else if (type == "quad") {
    parsed = read_quad(r);
  } else if (type == "disk") {
    parsed = read_disk(r);
  } else if (type == "directional") {
    parsed = read_directional(r);
  } else {
    parsed = read_environment(r, files);
  }
  r.finish();
  return parsed;
}

}  // namespace caligo
