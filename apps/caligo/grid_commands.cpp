// caligo generate cloud|smoke|fire -o FILE.vdb|FILE.nvdb [--res N] [--seed S]: a procedural
// volume written as a grid file. caligo info FILE: the grids a .vdb or .nvdb file holds.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "commands.h"
#include "core/error.h"
#include "core/output_transaction.h"
#include "grids/grid_generate.h"
#include "grids/grid_io.h"

namespace caligo {

void add_generate_command(CLI::App& app, GenerateOptions& o) {
  CLI::App* cmd =
      app.add_subcommand("generate", "Write a procedural volume (cloud, smoke, fire) as a grid file");
  cmd->add_option("kind", o.kind, "cloud, smoke or fire")->required();
  cmd->add_option("-o,--output", o.output, "Output grid file (.vdb or .nvdb)")->required();
  cmd->add_option("--res", o.resolution, "Voxels along the longest edge (8..1024, default 128)");
  cmd->add_option("--seed", o.seed, "Random seed (default 1)");
  cmd->add_flag("-q,--quiet", o.quiet, "Print nothing on success");
}

int run_generate(const GenerateOptions& o) {
  // Everything is checked before any work, so bad input writes nothing.
  const std::optional<GeneratedVolume> kind = parse_generated_volume(o.kind);
  if (!kind)
    throw InputError(kCommandLine, "unknown volume \"" + o.kind + "\" (choose cloud, smoke or fire)");
  if (o.resolution < kMinGenerateResolution || o.resolution > kMaxGenerateResolution)
    throw InputError(kCommandLine, "--res must be in [" + std::to_string(kMinGenerateResolution) + ", " +
                                       std::to_string(kMaxGenerateResolution) + "], got " +
                                       std::to_string(o.resolution));
  const uint64_t seed = parse_seed(o.seed);
  std::string ext = std::filesystem::path(o.output).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext != ".vdb" && ext != ".nvdb")
    throw InputError({o.output, ""}, "the output must end in .vdb (OpenVDB) or .nvdb (NanoVDB)");
  OutputTransaction output;
  output.add(o.output, "grid");  // a folder, a missing folder or a read-only one: refused now

  const auto start = std::chrono::steady_clock::now();
  const std::vector<SparseFloatGrid> grids = generate_grids({*kind, o.resolution, seed});
  const auto generated = std::chrono::steady_clock::now();
  output.commit({[&](const std::string& temp) { write_grid_file(temp, grids); }});
  const auto written = std::chrono::steady_clock::now();
  if (!o.quiet) {
    const auto ms = [](auto a, auto b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
    std::printf("wrote %s: %s at %d voxels (voxel %.4g m), seed %llu\n", o.output.c_str(), o.kind.c_str(),
                o.resolution, double(grids[0].voxel_size), static_cast<unsigned long long>(seed));
    for (const SparseFloatGrid& g : grids)
      std::printf("  %-12s %10llu active voxels in %6zu blocks\n", g.name.c_str(),
                  static_cast<unsigned long long>(g.active_voxels()), g.blocks.size());
    std::printf("generated in %.0f ms, written in %.0f ms (%llu bytes)\n", ms(start, generated),
                ms(generated, written),
                static_cast<unsigned long long>(std::filesystem::file_size(o.output)));
  }
  return 0;
}

void add_info_command(CLI::App& app, InfoOptions& o) {
  CLI::App* cmd = app.add_subcommand("info", "Describe the grids of a .vdb or .nvdb file");
  cmd->add_option("file", o.file, "Grid file (.vdb or .nvdb)")->required();
}

int run_info(const InfoOptions& o) {
  std::fputs(format_grid_file_info(describe_grid_file(o.file)).c_str(), stdout);
  return 0;
}

}  // namespace caligo
