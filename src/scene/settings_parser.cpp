#include "scene/settings_parser.h"

#include <cmath>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/math.h"
#include "scene/shared_readers.h"
#include "scene/transform_parser.h"
#include "settings/aov.h"

namespace caligo {
namespace {

constexpr double kMaxResolution = 16384;
constexpr double kMaxSpp = 1'000'000;
constexpr double kMaxBounces = 10'000;
constexpr double kMaxFrames = 100'000;
constexpr double kMaxFilterRadius = 16;  // pixels

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

// A key that only some kinds of camera read is an error on the others (it would be ignored).
void reject_key(ObjectReader& r, std::string_view key, const std::string& why) {
  if (auto c = r.optional(key)) c->fail("\"" + std::string(key) + "\" " + why);
}

// "aperture_radius" (metres) or "fstop" (f-number), and "focus_distance" (metres along the
// view axis): a thin lens. Neither aperture key, or a zero radius: a pinhole.
void read_lens(ObjectReader& r, CameraDesc& camera) {
  if (r.has("aperture_radius") && r.has("fstop"))
    r.fail("expected at most one of \"aperture_radius\" or \"fstop\" in " + r.what() + ", got both");
  camera.aperture_radius = r.number_or("aperture_radius", 0.0f, Range::non_negative());
  camera.fstop = r.number_or("fstop", 0.0f, Range::positive());
  if (camera.aperture_radius == 0.0f && camera.fstop == 0.0f)
    reject_key(r, "focus_distance", "needs an aperture: give \"aperture_radius\" > 0 or \"fstop\"");
  camera.focus_distance = r.number_or("focus_distance", 0.0f, Range::positive());
}

// "projection": "perspective" (default) or "orthographic" with "ortho_width" in metres.
void read_projection(ObjectReader& r, CameraDesc& camera) {
  const bool ortho = r.has("projection") && r.choice("projection", {"perspective", "orthographic"}) == "orthographic";
  if (!ortho) {
    reject_key(r, "ortho_width", "applies only to an orthographic camera (\"projection\": \"orthographic\")");
    read_lens(r, camera);
    return;
  }
  camera.projection = CameraProjection::orthographic;
  camera.ortho_width = r.number("ortho_width", Range::positive());
  for (const char* key : {"fov", "aperture_radius", "fstop", "focus_distance"})
    reject_key(r, key, "does not apply to an orthographic camera");
}

// With a path, "position" and "look_at" may be left out: the first key gives them.
}  // namespace

CameraDesc parse_camera(const JsonCursor& c) {
  ObjectReader r(c, "the camera");
  r.allow({"position", "look_at", "up", "fov", "resolution", "path", "projection", "ortho_width",
           "aperture_radius", "fstop", "focus_distance", "handedness"});
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
  read_projection(r, camera);
  if (r.has("handedness")) camera.left_handed = r.choice("handedness", {"right", "left"}) == "left";
  r.finish();
  return camera;
}

namespace {

// "filter": {"type": "box" | "gaussian" | "blackman_harris", "radius": pixels, "sigma": pixels}.
PixelFilterDesc read_pixel_filter(const JsonCursor& c) {
  ObjectReader r(c, "a pixel filter");
  r.allow({"type", "radius", "sigma"});
  const std::string type = r.choice("type", {"box", "gaussian", "blackman_harris"});
  r.set_what("a " + type + " pixel filter");
  PixelFilterDesc f;
  f.type = type == "box" ? PixelFilterType::box
                         : (type == "gaussian" ? PixelFilterType::gaussian : PixelFilterType::blackman_harris);
  f.radius = r.number_or("radius", PixelFilterDesc::default_radius(f.type), Range::above_up_to(0, kMaxFilterRadius));
  if (f.type == PixelFilterType::gaussian)
    f.sigma = r.number_or("sigma", f.sigma, Range::above_up_to(0, kMaxFilterRadius));
  else
    reject_key(r, "sigma", "applies only to a gaussian pixel filter");
  r.finish();
  return f;
}

// "crop": [x0, x1, y0, y1], fractions of the image from its left and top edges.
CropWindow read_crop(const JsonCursor& c) {
  if (!c.is_array() || c.json().size() != 4)
    c.fail("expected an array of 4 numbers [x0, x1, y0, y1], got " + c.describe());
  const auto e = c.elements("");
  const Range unit = Range::closed(0, 1);
  const CropWindow crop{e[0].number(unit), e[1].number(unit), e[2].number(unit), e[3].number(unit)};
  if (const std::string why = crop_window_problem(crop); !why.empty()) c.fail(why + ", got " + c.describe());
  return crop;
}

// "aovs": the names --aov takes (settings/aov.h), one per element; the beauty is always written.
AovSet read_aovs(const JsonCursor& c) {
  AovSet set;
  for (const JsonCursor& e : c.elements("an array of output names")) {
    const std::string name = e.string();
    try {
      if (name.find(',') != std::string::npos) throw InputError("a list");
      set = AovSet::from_bits(set.bits() | AovSet::parse(name).bits());
    } catch (const InputError&) {
      std::vector<std::string> names = {"beauty", "default", "all", "lights"};
      for (int a = 0; a < kAovCount; ++a) names.emplace_back(aov_name(Aov(a)));
      std::string message = "unknown output " + e.describe() + " in render.aovs";
      if (const std::string guess = closest_match(name, names); !guess.empty())
        message += " (did you mean \"" + guess + "\"?)";
      std::string list;
      for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
      e.fail(message + "; valid names: " + list);
    }
  }
  return set;
}

}  // namespace

RenderSettings parse_render(const JsonCursor& c) {
  ObjectReader r(c, "the render settings");
  r.allow({"spp", "max_bounces", "max_depth", "max_volume_bounces", "seed", "priority_shadows", "filter", "crop",
           "aovs", "guiding", "adaptive", "clamp"});
  RenderSettings render;
  render.spp = int(r.integer_or("spp", render.spp, Range::closed(1, kMaxSpp)));
  // "max_depth" is the former name of "max_bounces" (PathLimits), kept as an alias.
  const auto old_name = r.optional("max_depth");
  if (old_name && r.has("max_bounces"))
    old_name->fail("\"max_depth\" is an alias of \"max_bounces\" in " + r.what() + "; give one of them, not both");
  const auto bounces = old_name ? old_name : r.optional("max_bounces");
  if (bounces) render.path.limits.max_bounces = int(bounces->integer(Range::closed(0, kMaxBounces)));
  render.path.limits.max_volume_bounces =
      int(r.integer_or("max_volume_bounces", render.path.limits.max_volume_bounces, Range::closed(0, kMaxBounces)));
  if (auto seed = r.optional("seed")) render.seed = seed->unsigned_integer();
  render.path.priority_shadows = r.boolean_or("priority_shadows", render.path.priority_shadows);
  if (auto f = r.optional("filter")) render.filter = read_pixel_filter(*f);
  if (auto crop = r.optional("crop")) render.crop = read_crop(*crop);
  if (auto aovs = r.optional("aovs")) render.aovs = read_aovs(*aovs);
  if (r.has("guiding")) {
    const std::string mode = r.choice("guiding", {"off", "surface", "volume", "all"});
    render.path.guiding = *enum_from_name(kGuidingModeNames, mode);
  }
  if (auto a = r.optional("adaptive")) {
    ObjectReader ar(*a, "the adaptive sampling settings");
    ar.allow({"threshold", "min_samples"});
    render.adaptive.threshold = float(ar.number_or("threshold", 0.01, Range::above_up_to(0, 1)));
    render.adaptive.min_samples = int(ar.integer_or("min_samples", 0, Range::closed(0, kMaxSpp)));
    ar.finish();
    render.aovs = render.aovs.with(Aov::kVariance);  // the error each pixel stops by
  }
  if (auto c = r.optional("clamp")) {
    ObjectReader cr(*c, "the sample clamp");
    cr.allow({"direct", "indirect"});
    render.clamp.direct = float(cr.number_or("direct", 0.0, Range::non_negative()));
    render.clamp.indirect = float(cr.number_or("indirect", 0.0, Range::non_negative()));
    cr.finish();
  }
  r.finish();
  return render;
}

RealtimeSettings parse_realtime(const JsonCursor& c) {
  ObjectReader r(c, "the realtime settings");
  r.allow({"scale", "tile_size", "samples", "gather_radius", "gather_depth_falloff", "gather_follow_slope",
           "temporal", "temporal_blend", "multiple_scattering_floor", "steps", "froxels", "fps", "frames",
           "environment_lights", "shadow_filter", "low_depth", "sun_cascades", "light_depth_cells"});
  RealtimeSettings d;
  if (r.has("scale")) {
    const std::string scale = r.choice("scale", {"full", "half", "quarter"});
    d.scale = scale == "full" ? 1 : (scale == "half" ? 2 : 4);
  }
  d.accumulation.tile_size = int(r.integer_or("tile_size", d.accumulation.tile_size, Range::closed(1, 32)));
  d.accumulation.samples = int(r.integer_or("samples", d.accumulation.samples, Range::closed(1, 1024)));
  d.gather_radius = int(r.integer_or("gather_radius", d.gather_radius, Range::closed(0, 16)));
  d.gather_depth_falloff = r.number_or("gather_depth_falloff", d.gather_depth_falloff, Range::positive());
  d.gather_follow_slope = r.boolean_or("gather_follow_slope", d.gather_follow_slope);
  d.temporal = r.boolean_or("temporal", d.temporal);
  if (auto f = r.optional("froxels")) {
    // The grid of `caligo realtime --method froxel`.
    ObjectReader fr(*f, "the froxel grid");
    fr.allow({"width", "height", "column_pixels", "slices", "near_ratio"});
    d.froxels.width = int(fr.integer_or("width", d.froxels.width, Range::closed(1, 1024)));
    d.froxels.height = int(fr.integer_or("height", d.froxels.height, Range::closed(1, 1024)));
    d.froxels.column_pixels = int(fr.integer_or("column_pixels", d.froxels.column_pixels, Range::closed(1, 256)));
    d.froxels.slices = int(fr.integer_or("slices", d.froxels.slices, Range::closed(2, 512)));
    d.froxels.near_ratio = fr.number_or("near_ratio", d.froxels.near_ratio, Range::closed(2, 1e6));
    fr.finish();
  }
  d.temporal_blend = r.number_or("temporal_blend", d.temporal_blend, Range::above_up_to(0, 1));
  if (r.has("low_depth"))
    d.low_depth = r.choice("low_depth", {"min_max", "centre"}) == "min_max" ? LowResolutionDepth::min_max
                                                                            : LowResolutionDepth::centre;
  if (r.has("shadow_filter")) d.filter_surface_shadows = r.choice("shadow_filter", {"bilinear", "none"}) == "bilinear";
  d.environment_lights =
      int(r.integer_or("environment_lights", d.environment_lights, Range::closed(1, 256)));
  d.sun_cascades = int(r.integer_or("sun_cascades", d.sun_cascades, Range::closed(1, 8)));
  d.light_depth_cells = int(r.integer_or("light_depth_cells", d.light_depth_cells, Range::closed(0, 512)));
  d.accumulation.multiple_scattering_floor =
      r.number_or("multiple_scattering_floor", d.accumulation.multiple_scattering_floor, Range::closed(0, 1));
  if (r.has("steps")) d.accumulation.equiangular = r.choice("steps", {"uniform", "equiangular"}) == "equiangular";
  d.fps = r.number_or("fps", d.fps, Range::positive());
  d.frames = int(r.integer_or("frames", d.frames, Range::closed(1, kMaxFrames)));
  r.finish();
  return d;
}

}  // namespace caligo
