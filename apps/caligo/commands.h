// The subcommands of the caligo command line; each lives in its own file.
#pragma once

#include <optional>
#include <string>

namespace CLI {
class App;
}

namespace caligo {

struct RenderOptions {
  std::string scene;   // a scene file or a built-in's name
  std::string output;  // .exr path; a .png preview is written beside it
  std::optional<int> spp;
  std::optional<std::string> resolution;  // "WxH"
  std::optional<int> threads;
  std::optional<uint64_t> seed;
  std::optional<int> max_depth;
  std::optional<int> max_volume_bounces;
  std::optional<std::string> distance_sampling;
  float exposure = 0.0f;
  bool list_builtins = false;
  bool quiet = false;
};

struct CompareOptions {
  std::string a, b;
  std::optional<double> max_rmse;
};

void add_render_command(CLI::App& app, RenderOptions& options);
void add_compare_command(CLI::App& app, CompareOptions& options);
int run_render(const RenderOptions& options);
int run_compare(const CompareOptions& options);

}  // namespace caligo
