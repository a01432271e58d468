// What the subcommands share: the scene argument and the resolution option.
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <system_error>

#include "commands.h"
#include "core/error.h"
#include "scene/builtins.h"
#include "scene/scene_parser.h"

namespace caligo {

Vec2i parse_resolution(const std::string& text) {
  int w = 0, h = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X'))
    throw InputError(kCommandLine, "--res: expected WxH such as 640x480, got " + quote_for_message(text));
  if (w < 1 || h < 1 || w > 16384 || h > 16384)
    throw InputError(kCommandLine,
                     "--res: each side must be between 1 and 16384, got " + quote_for_message(text));
  return {w, h};
}

uint64_t parse_seed(const std::string& text) {
  int64_t value = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (text.empty() || ec != std::errc() || ptr != end || value < 0)
    throw InputError(kCommandLine, "--seed: expected an integer from 0 to 9223372036854775807, got " +
                                       quote_for_message(text));
  return uint64_t(value);
}

SceneDesc load_scene(const std::string& name, std::optional<int> frame) {
  if (name.empty()) throw InputError(kCommandLine, "no scene given (a .json file or a built-in name)");
  if (const BuiltinScene* builtin = find_builtin(name))
    return parse_scene_text(builtin->json, "builtin:" + builtin->name, ".");
  std::error_code ec;
  const bool exists = std::filesystem::exists(name, ec);
  if (ec && ec != std::errc::no_such_file_or_directory)  // a symlink loop, a folder we may not enter
    throw InputError(SourceLocation{name, ""}, "cannot read the scene file: " + ec.message());
  if (!exists) {
    std::string names;
    for (const BuiltinScene& b : builtin_scenes()) names += (names.empty() ? "" : ", ") + b.name;
    throw InputError(SourceLocation{name, ""},
                     "no such scene file, and no built-in of that name (built-ins: " + names + ")");
  }
  return parse_scene_file(name, frame);
}

void print_scene_warnings(const SceneDesc& desc) {
  for (const std::string& w : desc.warnings) std::fprintf(stderr, "caligo: warning: %s\n", w.c_str());
}

}  // namespace caligo
