// caligo scene list | caligo scene show NAME: the built-in scenes as text, the natural start
// for a scene of one's own ("a cloud like `cloud`, but mine": show it, redirect, edit).
#include <CLI/CLI.hpp>

#include <cstdio>

#include "commands.h"
#include "core/error.h"
#include "scene/builtins.h"

namespace caligo {

void add_scene_command(CLI::App& app, SceneCommandOptions& o) {
  CLI::App* cmd = app.add_subcommand("scene", "List the built-in scenes or print one's JSON");
  cmd->require_subcommand(1);
  CLI::App* list = cmd->add_subcommand("list", "List the built-in scenes with a line each");
  list->callback([&o] { o.action = SceneCommandOptions::kList; });
  CLI::App* show = cmd->add_subcommand("show", "Print a built-in scene's JSON (save it with > my-scene.json)");
  show->add_option("name", o.name, "A built-in's name (see `caligo scene list`)")->required();
  show->callback([&o] { o.action = SceneCommandOptions::kShow; });
}

int run_scene(const SceneCommandOptions& o) {
  if (o.action == SceneCommandOptions::kList) {
    for (const BuiltinScene& b : builtin_scenes()) std::printf("%-18s %s\n", b.name.c_str(), b.description.c_str());
    return 0;
  }
  const BuiltinScene* builtin = find_builtin(o.name);
  if (!builtin) {
    std::string names;
    for (const BuiltinScene& b : builtin_scenes()) names += (names.empty() ? "" : ", ") + b.name;
    throw InputError(kCommandLine, "scene show: no built-in called " + quote_for_message(o.name) + " (built-ins: " +
                                       names + ")");
  }
  // Builtins name their files by absolute paths (or generate them), so the text renders from
  // wherever it is saved.
  std::fwrite(builtin->json.data(), 1, builtin->json.size(), stdout);
  if (!builtin->json.empty() && builtin->json.back() != '\n') std::fputc('\n', stdout);
  return std::fflush(stdout) == 0 && !std::ferror(stdout) ? 0 : kExitEnvironmentError;
}

}  // namespace caligo
