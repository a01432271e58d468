// Readers shared by the scene, light and volume parsers: aiming, parallel checks, file paths,
// keyframe timing. Every failure is a located InputError (see json_reader.h).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scene/json_reader.h"
#include "scene/scene_desc.h"

namespace caligo {

// Two unit vectors closer than this (|cross|, i.e. the sine of their angle) count as parallel.
inline constexpr float kParallelSine = 1e-4f;
bool parallel(Vec3 a, Vec3 b);

// The direction from `from` to the point at `target`, which must differ from `from`.
Vec3 read_target_direction(const JsonCursor& target, Vec3 from, std::string_view from_name);

// corner + s*edge1 + t*edge2: both edges non-zero and not parallel.
void read_parallelogram(ObjectReader& r, Vec3& corner, Vec3& edge1, Vec3& edge2);

// A file name relative to the scene file's directory (left as written when base_dir is empty).
std::string resolve_path(const std::string& file, const std::string& base_dir);

// The files one scene names: relative names resolve against base_dir, and each resolved path
// is recorded (SceneDesc::files), so that commands refuse an output that would replace an
// input and checkpoints are keyed on the inputs too.
struct SceneFiles {
  std::string base_dir;
  std::vector<std::string> named;  // resolved, each once, in the order first named
  // What the files' reading found worth a warning (a located message each; SceneDesc::warnings).
  std::vector<std::string> warnings;
  // The frame of a sequence render: "{frame}" in file names becomes it (core/frame_pattern.h).
  std::optional<int> frame;
  std::string resolve(const std::string& file);
  // The string at `c`, its frame pattern substituted, resolved; a pattern without a frame to
  // render, or a malformed one, fails at `c`.
  std::string resolve(const JsonCursor& c);
};

// [u, v]: an array of two numbers within `range`.
Vec2 read_vec2(const JsonCursor& c, Range range = Range::any());

// "interpolation": "linear" (default) or "catmull_rom".
Interpolation read_interpolation(ObjectReader& r);

// The "time" of one key of an array of keys; must exceed `previous` (times increase strictly).
float read_key_time(ObjectReader& r, const float* previous);

}  // namespace caligo
