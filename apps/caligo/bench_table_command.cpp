// caligo bench-table wyman [--res N] [--scales 1,4] [--frames F] [--reference-spp S] [--scenes a,b] [-o DIR]
// The command line of the paper tables: options, their checks, the output folder, progress on
// stderr, the markdown on stdout and in DIR/table.md, one previews PNG per scene. The
// experiment itself, and what it measures, is src/experiments/wyman_table.h.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.h"
#include "output_folder.h"
#include "render_outputs.h"
#include "core/output_transaction.h"
#include "experiments/wyman_table.h"
#include "image/png_io.h"

namespace caligo {

void add_bench_table_command(CLI::App& app, BenchTableOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "bench-table",
      "Reproduce a paper's table on the built-in scenes (wyman: Wyman & Ramsey 2008, Table 1)");
  cmd->add_option("table", o.table, "Which table: wyman");
  cmd->add_option("--res", o.resolution, "Square output resolution N (NxN)");
  cmd->add_option("--scales", o.scales, "Accumulation scales, comma separated (1: full resolution, 4: 1/4)");
  cmd->add_option("--frames", o.frames, "Timed frames per method after the warm-up");
  cmd->add_option("--reference-spp", o.reference_spp, "Samples per pixel of the path-traced reference");
  cmd->add_option("--scenes", o.scenes, "Scenes, comma separated (default: the four wyman-* built-ins)");
  cmd->add_option("-o,--output", o.output, "A folder for table.md and one PNG per scene");
  cmd->add_option("--exposure", o.exposure, "Exposure of the PNGs, in stops");
}

namespace {

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> parts;
  size_t start = 0;
  while (true) {
    const size_t comma = text.find(',', start);
    parts.push_back(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) return parts;
    start = comma + 1;
  }
}

std::vector<int> parse_ints(const std::string& text, const char* option, int lo, int hi) {
  std::vector<int> values;
  for (const std::string& part : split(text)) {
    int v = 0;
    const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), v);
    if (part.empty() || ec != std::errc() || end != part.data() + part.size() || v < lo || v > hi)
      throw InputError(kCommandLine, std::string(option) + ": expected comma-separated integers " +
                                         std::to_string(lo) + " to " + std::to_string(hi) + ", got \"" +
                                         text + "\"");
    values.push_back(v);
  }
  return values;
}

void check_range(int v, int lo, int hi, const char* option) {
  if (v < lo || v > hi)
    throw InputError(kCommandLine, std::string(option) + ": expected " + std::to_string(lo) + " to " +
                                       std::to_string(hi) + ", got " + std::to_string(v));
}

WymanTableSettings wyman_settings(const BenchTableOptions& o) {
  if (o.table != "wyman")
    throw InputError(kCommandLine, "bench-table: expected a table name: wyman, got \"" + o.table + "\"");
  check_range(o.resolution, 8, 8192, "--res");
  check_range(o.frames, 1, 10000, "--frames");
  check_range(o.reference_spp, 1, 1'000'000, "--reference-spp");
  if (!std::isfinite(o.exposure)) throw InputError(kCommandLine, "--exposure: expected a finite number");
  WymanTableSettings s;
  s.resolution = o.resolution;
  s.scales = parse_ints(o.scales, "--scales", 1, 16);
  s.frames = o.frames;
  s.reference_spp = o.reference_spp;
  if (!o.scenes.empty()) s.scenes = split(o.scenes);
  s.exposure = o.exposure;
  return s;
}

std::string png_name(const std::string& scene) {
  return std::filesystem::path(scene).stem().string() + ".png";
}

}  // namespace

int run_bench_table(const BenchTableOptions& o) {
  const WymanTableSettings settings = wyman_settings(o);
  const std::vector<WymanScene> scenes = load_wyman_scenes(settings, [](const std::string& name) { return load_scene(name); });  // fail before work
  // The outputs, one transaction planned now: a strip per scene, then the table.
  std::optional<OutputFolder> folder;
  OutputTransaction outputs;
  const auto output_path = [&](const std::string& name) { return (std::filesystem::path(o.output) / name).string(); };
  if (!o.output.empty()) {
    for (const WymanScene& scene : scenes) protect_scene_inputs(outputs, scene.desc);
    folder.emplace(o.output);
    for (const std::string& n : settings.scenes) outputs.add(output_path(png_name(n)), "strip");
    outputs.add(output_path("table.md"), "table");
  }

  WymanTableHooks hooks;
  hooks.progress = [](const std::string& line) { std::fprintf(stderr, "bench-table: %s\n", line.c_str()); };
  if (!o.output.empty())
    hooks.preview = [&](const std::string& scene, const Rgb8Image& strip) {
      const auto it = std::find(settings.scenes.begin(), settings.scenes.end(), scene);
      outputs.stage(size_t(it - settings.scenes.begin()), [&](const std::string& temp) {
        write_png(temp, strip.width, strip.height, strip.rgb);
      });
    };
  const std::string md = wyman_markdown(run_wyman_table(settings, scenes, hooks));
  std::fputs(md.c_str(), stdout);
  if (!o.output.empty()) {
    outputs.stage(outputs.size() - 1, [&](const std::string& temp) {
      std::ofstream out(temp);
      out << md;
      out.close();
      if (!out) throw std::runtime_error("cannot write the table");
    });
    outputs.commit();
    folder->keep();
    std::string pngs;
    for (const std::string& n : settings.scenes) pngs += " " + png_name(n);
    std::printf(
        "-> %s, per scene (rows: scales; columns: none, brute 150, hybrid 50, textured, march, reference, "
        "spot reference):%s\n",
        output_path("table.md").c_str(), pngs.c_str());
  }
  return 0;
}

}  // namespace caligo
