#include "scene/shared_readers.h"

#include "core/frame_pattern.h"

#include <algorithm>
#include <filesystem>

#include <nlohmann/json.hpp>

namespace caligo {

bool parallel(Vec3 a, Vec3 b) { return length(cross(normalize(a), normalize(b))) < kParallelSine; }

Vec3 read_target_direction(const JsonCursor& target, Vec3 from, std::string_view from_name) {
  const Vec3 to = target.vec3();
  if (!(length_squared(to - from) > 0.0f))
    target.fail("expected a point different from " + std::string(from_name) + " " + format_vec3(from) +
                ", got the same point");
  return normalize(to - from);
}

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

std::string resolve_path(const std::string& file, const std::string& base_dir) {
  std::filesystem::path p(file);
  if (p.is_relative() && !base_dir.empty()) p = std::filesystem::path(base_dir) / p;
  return p.lexically_normal().string();
}

std::string SceneFiles::resolve(const std::string& file) {
  std::string path = resolve_path(file, base_dir);
  if (std::find(named.begin(), named.end(), path) == named.end()) named.push_back(path);
  return path;
}

std::string SceneFiles::resolve(const JsonCursor& c) {
  std::string file = c.string();
  if (has_frame_pattern(file)) {
    if (!frame)
      c.fail("the file name has a {frame} pattern, but no frame is rendered (render --frames A..B)");
    std::string error;
    const std::optional<std::string> named_frame = substitute_frame(file, *frame, &error);
    if (!named_frame) c.fail(error);
    file = *named_frame;
  }
  return resolve(file);
}

Vec2 read_vec2(const JsonCursor& c, Range range) {
  if (!c.is_array() || c.json().size() != 2) c.fail("expected an array of 2 numbers, got " + c.describe());
  const auto e = c.elements("");
  return {e[0].number(range), e[1].number(range)};
}

Interpolation read_interpolation(ObjectReader& r) {
  if (!r.has("interpolation")) return Interpolation::linear;
  return r.choice("interpolation", {"linear", "catmull_rom"}) == "linear" ? Interpolation::linear
                                                                          : Interpolation::catmull_rom;
}

float read_key_time(ObjectReader& r, const float* previous) {
  const JsonCursor c = r.required("time");
  const float t = c.number(Range::non_negative());
  if (previous && !(t > *previous))
    c.fail("expected a time after the previous key's " + format_number(*previous) +
           " (times increase), got " + c.describe());
  return t;
}

}  // namespace caligo
