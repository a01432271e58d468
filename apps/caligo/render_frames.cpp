// caligo render --frames A..B: a sequence, one frame after another, each its own render with
// its own output transaction (a frame written is complete; an interrupt keeps what is done).
// "{frame}" in -o and in the scene's file names (one VDB per frame, as effects tools export)
// becomes the frame's number; the scene's time is frame / --fps.
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <utility>

#include "commands.h"
#include "core/error.h"
#include "core/frame_pattern.h"

namespace caligo {
namespace {

int parse_frame_number(std::string_view text, const std::string& whole) {
  int value = -1;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size() || value < 0 || value > 1'000'000)
    throw InputError(kCommandLine, "--frames: expected A..B or N with frames from 0 to 1000000, got " + quote_for_message(whole));
  return value;
}

std::string frame_output(const std::string& pattern, int frame) {
  std::string error;
  const std::optional<std::string> path = substitute_frame(pattern, frame, &error);
  if (!path) throw InputError(kCommandLine, "-o: " + error);
  return *path;
}

}  // namespace

std::pair<int, int> parse_frame_range(const std::string& text) {
  const size_t dots = text.find("..");
  const int first = parse_frame_number(std::string_view(text).substr(0, dots), text);
  const int last = dots == std::string::npos ? first : parse_frame_number(std::string_view(text).substr(dots + 2), text);
  if (last < first) throw InputError(kCommandLine, "--frames: the last frame comes before the first in " + quote_for_message(text));
  if (last - first >= 100000) throw InputError(kCommandLine, "--frames: at most 100000 frames in one command");
  return {first, last};
}

int run_render_sequence(const RenderOptions& o) {
  const auto [first, last] = parse_frame_range(*o.frames);
  if (o.checkpoint || o.resume) throw InputError(kCommandLine, "--frames renders each frame once: no --checkpoint or --resume");
  if (o.time != 0.0f) throw InputError(kCommandLine, "--frames sets each frame's time (frame / --fps): no --time");
  if (!(o.fps > 0.0f && o.fps <= 1000.0f)) throw InputError(kCommandLine, "--fps: expected frames per second in (0, 1000]");
  const std::string pattern = o.output ? *o.output : std::filesystem::path(o.scene).stem().string() + "_{frame:04}.exr";
  if (last > first && !has_frame_pattern(pattern))
    throw InputError(kCommandLine, "-o " + quote_for_message(pattern) + " has no {frame} pattern: every frame would "
                                   "overwrite the one before (e.g. -o out/smoke_{frame:04}.exr)");
  for (int frame = first; frame <= last; ++frame) {
    RenderOptions one = o;
    one.frames.reset();
    one.frame = frame;
    one.time = float(frame) / o.fps;
    one.output = frame_output(pattern, frame);
    if (!o.quiet && last > first) std::fprintf(stderr, "caligo: frame %d (%d of %d)\n", frame, frame - first + 1, last - first + 1);
    if (const int code = run_render(one); code != 0) return code;  // an interrupt: the finished frames stay
  }
  return 0;
}

}  // namespace caligo
