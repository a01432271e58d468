// caligo: the command line. Exit codes: 0 success, 1 internal error (a bug of ours),
// 2 bad input (scene, mesh, image or command line), with a one-line message on stderr.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>

#include "commands.h"
#include "core/error.h"
#include "distributed/rank_failure.h"

namespace {

// A safety net under the messages' own quoting (core/message_text.h): whatever a message
// holds, it is printed as one line of bounded length with control characters escaped.
int print_error(const char* what, int code) {
  const std::string line = caligo::printable_for_message(what, caligo::kMessageLineBytes);
  std::fprintf(stderr, "caligo: error: %s\n", line.c_str());
  return code;
}

// CLI11 would only say "a subcommand is required" for a misspelt one.
bool report_unknown_command(const CLI::App& app, int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') return false;
  for (const CLI::App* sub : app.get_subcommands({}))
    if (sub->check_name(argv[1])) return false;
  std::fprintf(stderr,
               "caligo: error: unknown command %s (commands: render, realtime, compare, generate, info, "
               "scene, bench-table)\n",
               caligo::quote_for_message(argv[1]).c_str());
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Caligo: a renderer for participating media", "caligo"};
  app.set_version_flag("--version", std::string("caligo ") + CALIGO_VERSION);
  app.require_subcommand(1);
  caligo::RenderOptions render;
  caligo::CompareOptions compare;
  caligo::RealtimeOptions realtime;
  caligo::add_render_command(app, render);
  caligo::add_realtime_command(app, realtime);
  caligo::add_compare_command(app, compare);
  caligo::GenerateOptions generate;
  caligo::InfoOptions info;
  caligo::add_generate_command(app, generate);
  caligo::add_info_command(app, info);
  caligo::SceneCommandOptions scene;
  caligo::add_scene_command(app, scene);
  caligo::BenchTableOptions bench_table;
  caligo::add_bench_table_command(app, bench_table);
  caligo::DenoiseOptions denoise;
  caligo::add_denoise_command(app, denoise);
  if (report_unknown_command(app, argc, argv)) return caligo::kExitInputError;
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    print_error(e.what(), caligo::kExitInputError);
    std::fprintf(stderr, "run 'caligo --help' for usage\n");
    return caligo::kExitInputError;
  }
  try {
    if (app.got_subcommand("render")) return caligo::run_render(render);
    if (app.got_subcommand("compare")) return caligo::run_compare(compare);
    if (app.got_subcommand("realtime")) return caligo::run_realtime(realtime);
    if (app.got_subcommand("generate")) return caligo::run_generate(generate);
    if (app.got_subcommand("info")) return caligo::run_info(info);
    if (app.got_subcommand("scene")) return caligo::run_scene(scene);
    if (app.got_subcommand("bench-table")) return caligo::run_bench_table(bench_table);
    if (app.got_subcommand("denoise")) return caligo::run_denoise(denoise);
  } catch (const caligo::distributed::RankFailure& e) {
    return e.exit_code();  // an MPI job failed: rank 0 printed why
  } catch (const caligo::InputError& e) {
    return print_error(e.what(), caligo::kExitInputError);
  } catch (const caligo::EnvironmentError& e) {
    return print_error(e.what(), caligo::kExitEnvironmentError);
  } catch (const std::exception& e) {
    return print_error((std::string("internal: ") + e.what()).c_str(), caligo::kExitInternalError);
  }
  return caligo::kExitInternalError;
}
