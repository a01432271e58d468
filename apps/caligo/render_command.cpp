// caligo render [SCENE.json | BUILTIN] [-o out.exr] [--spp N] [--res WxH] [--threads N] [--seed S]
//               [--priority MATERIAL=LEVEL ...] [--light-sampler tree|power|uniform]
#include <CLI/CLI.hpp>

#include <cstdio>
#include <cstdlib>
#include <optional>
#include <filesystem>
#include <string>

#include "commands.h"
#include "core/error.h"
#include "image/exr_io.h"
#include "image/png_io.h"
#include "image/tonemap.h"
#include "render/render.h"
#include "scene/builtins.h"
#include "scene/material_priority.h"
#include "scene/scene_parser.h"

namespace caligo {

void add_render_command(CLI::App& app, RenderOptions& o) {
  CLI::App* cmd = app.add_subcommand("render", "Render a scene file or a built-in scene to OpenEXR + PNG");
  cmd->add_option("scene", o.scene, "Scene file (.json) or built-in name (see --list-builtins)");
  cmd->add_option("-o,--output", o.output, "Output OpenEXR file; a PNG preview is written beside it")
      ->default_str("<scene name>.exr");
  cmd->add_option("--spp", o.spp, "Samples per pixel (overrides the scene)");
  cmd->add_option("--res", o.resolution, "Resolution WxH, e.g. 640x480 (overrides the scene)");
  cmd->add_option("--threads", o.threads, "Worker threads (default: all cores)");
  cmd->add_option("--seed", o.seed, "Random seed (overrides the scene)");
  cmd->add_option("--max-bounces,--max-depth", o.max_bounces,
                  "Maximum bounces: each surface bounce and each run of consecutive scattering events in "
                  "media counts one; 1 is direct light only (overrides the scene; --max-depth is an alias)");
  cmd->add_option("--max-volume-bounces", o.max_volume_bounces,
                  "Maximum scattering events in media, runs included (overrides the scene)");
  cmd->add_option("--distance-sampling", o.distance_sampling,
                  "Distance sampling for light in media: mis (default; equiangular share by optical depth), mis-fixed (share 3/4), density or equiangular");
  cmd->add_option("--deferred-nee", o.deferred_nee,
                  "Connect K scattering vertices per path to lights after building it (0: each segment as it goes)");
  cmd->add_option("--light-sampler", o.light_sampler,
                  "How next-event estimation picks a light: tree (light tree: importance at the receiver), "
                  "power (in proportion to power, the same everywhere) or uniform")
      ->default_str(light_sampler_name(PathSettings{}.light_sampler));
  cmd->add_option("--filter", o.filter,
                  "Pixel filter, importance-sampled: box (radius 0.5 px), gaussian (radius 1.5, sigma 0.5) or "
                  "blackman_harris (radius 0.75, Cycles' width 1.5) (overrides the scene's render.filter)");
  cmd->add_option("--crop", o.crop,
                  "x0,x1,y0,y1: render only this part of the image, as fractions of its width and height from "
                  "the top-left corner, e.g. 0.25,0.75,0,0.5 (overrides the scene's render.crop)");
  cmd->add_option("--time", o.time, "Render the scene at this time in seconds (camera path, light keys)");
  cmd->add_option("--exposure", o.exposure, "Exposure of the PNG preview, in stops");
  cmd->add_option("--priority", o.priorities,
                  "MATERIAL=LEVEL: set a medium-bounding material's priority (an integer, or off, very_high, "
                  "high, normal, low, very_low); repeatable")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  cmd->add_flag("--list-builtins", o.list_builtins, "List the built-in scenes and exit");
  cmd->add_flag("-q,--quiet", o.quiet, "No progress output");
}

namespace {

// The options that override PathSettings, the scene's limits included.
void apply_path_options(const RenderOptions& o, PathSettings& path) {
  if (o.max_bounces) {
    if (*o.max_bounces < 0 || *o.max_bounces > 10'000)
      throw InputError(kCommandLine, "--max-bounces: expected 0 to 10000");
    path.limits.max_bounces = *o.max_bounces;
  }
  if (o.max_volume_bounces) {
    if (*o.max_volume_bounces < 0 || *o.max_volume_bounces > 10'000)
      throw InputError(kCommandLine, "--max-volume-bounces: expected 0 to 10000");
    path.limits.max_volume_bounces = *o.max_volume_bounces;
  }
  if (o.distance_sampling) {
    const std::string& d = *o.distance_sampling;
    if (d == "mis")
      path.distance_sampling = DistanceSampling::kMis;
    else if (d == "density")
      path.distance_sampling = DistanceSampling::kDensity;
    else if (d == "equiangular")
      path.distance_sampling = DistanceSampling::kEquiangular;
    else if (d == "mis-fixed")
      path.distance_sampling = DistanceSampling::kMisFixed;
    else
      throw InputError(kCommandLine, "--distance-sampling: expected mis, mis-fixed, density or equiangular, got \"" +
                                         d + "\"");
  }
  if (o.deferred_nee) {
    if (*o.deferred_nee < 0 || *o.deferred_nee > 64)
      throw InputError(kCommandLine, "--deferred-nee: expected 0 to 64, got " + std::to_string(*o.deferred_nee));
    path.deferred_nee = *o.deferred_nee;
  }
  if (o.light_sampler) {
    const auto kind = light_sampler_from_name(*o.light_sampler);
    if (!kind)
      throw InputError(kCommandLine, "--light-sampler: expected tree, power or uniform, got \"" + *o.light_sampler + "\"");
    path.light_sampler = *kind;
  }
}

// --crop x0,x1,y0,y1.
CropWindow parse_crop(const std::string& text) {
  const std::string expected = "--crop: expected x0,x1,y0,y1 (fractions of the image in [0, 1]), got \"" + text + "\"";
  float v[4];
  size_t start = 0;
  for (int i = 0; i < 4; ++i) {
    const size_t comma = i < 3 ? text.find(',', start) : text.size();
    if (comma == std::string::npos) throw InputError(kCommandLine, expected);
    const std::string part = text.substr(start, comma - start);
    char* end = nullptr;
    v[i] = std::strtof(part.c_str(), &end);
    if (part.empty() || end != part.c_str() + part.size()) throw InputError(kCommandLine, expected);
    start = comma + 1;
  }
  const CropWindow crop{v[0], v[1], v[2], v[3]};
  if (const std::string why = crop_window_problem(crop); !why.empty())
    throw InputError(kCommandLine, "--crop " + text + ": " + why);
  return crop;
}

// --filter and --crop; a crop (from either source) must hold a pixel at the final resolution.
void apply_image_options(const RenderOptions& o, const SceneDesc& desc, RenderSettings& s) {
  if (o.filter) {
    const auto type = pixel_filter_type_from_name(*o.filter);
    if (!type)
      throw InputError(kCommandLine, "--filter: expected box, gaussian or blackman_harris, got \"" + *o.filter + "\"");
    s.filter = PixelFilter({*type, PixelFilterDesc::default_radius(*type), PixelFilterDesc{}.sigma});
  }
  if (o.crop) s.crop = parse_crop(*o.crop);
  if (s.crop.pixels(s.resolution).empty()) {
    const SourceLocation where = o.crop ? kCommandLine : SourceLocation{desc.file, "/render/crop"};
    throw InputError(where, "the crop window holds no pixel at " + std::to_string(s.resolution.x) + "x" +
                                std::to_string(s.resolution.y));
  }
}

// The scene's settings with every option of the command line applied.
RenderSettings settings_from(const RenderOptions& o, const SceneDesc& desc) {
  RenderSettings s = default_settings(desc);
  if (o.spp) {
    if (*o.spp < 1 || *o.spp > 1'000'000) throw InputError(kCommandLine, "--spp: expected 1 to 1000000");
    s.spp = *o.spp;
  }
  if (o.resolution) s.resolution = parse_resolution(*o.resolution);
  // The film and the image hold ~100 bytes per pixel: cap the total so an absurd (but
  // per-side valid) resolution is an input error, not an out-of-memory crash.
  constexpr uint64_t kMaxPixels = uint64_t(1) << 26;  // 64 Mpixel, ~6.7 GB
  const uint64_t pixels = uint64_t(s.resolution.x) * uint64_t(s.resolution.y);
  if (pixels > kMaxPixels) {
    const SourceLocation where =
        o.resolution ? kCommandLine : SourceLocation{desc.file, "/camera/resolution"};
    throw InputError(where, "resolution " + std::to_string(s.resolution.x) + "x" +
                                std::to_string(s.resolution.y) + " has " + std::to_string(pixels) +
                                " pixels; at most " + std::to_string(kMaxPixels) + " are allowed");
  }
  if (o.threads) {
    if (*o.threads < 1 || *o.threads > 1024) throw InputError(kCommandLine, "--threads: expected 1 to 1024");
    s.threads = *o.threads;
  }
  if (o.seed) s.seed = *o.seed;
  apply_path_options(o, s.path);
  apply_image_options(o, desc, s);
  return s;
}

std::string default_output(const std::string& scene) {
  return std::filesystem::path(scene).stem().string() + ".exr";
}

// Checks the output location before rendering, so a long render never ends in a failed write.
void check_output(const std::filesystem::path& exr) {
  if (exr.extension() != ".exr")
    throw InputError(SourceLocation{exr.string(), ""}, "output must be an .exr file");
  const std::filesystem::path dir = exr.parent_path().empty() ? "." : exr.parent_path();
  if (!std::filesystem::is_directory(dir))
    throw InputError(SourceLocation{exr.string(), ""},
                     "output directory \"" + dir.string() + "\" does not exist");
}

void print_summary(const std::string& scene, const RenderSettings& s, const RenderStats& stats,
                   const std::string& output) {
  std::fprintf(stderr, "caligo: %s %dx%d, %d spp: %s wall, %.3g paths/s, %.3g rays/s, %d threads -> %s\n",
               scene.c_str(), s.resolution.x, s.resolution.y, s.spp, format_duration(stats.seconds).c_str(),
               double(stats.paths) / stats.seconds, double(stats.rays) / stats.seconds,
               s.threads > 0 ? s.threads : int(std::thread::hardware_concurrency()), output.c_str());
}

// --priority MATERIAL=LEVEL. Only materials that already bound a medium may change (the scene
// checked that their shapes are closed or marked open); a material with an interior medium
// may not be turned off.
void apply_priority(const std::string& arg, SceneDesc& desc) {
  const size_t eq = arg.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == arg.size())
    throw InputError(kCommandLine, "--priority: expected MATERIAL=LEVEL, got \"" + arg + "\"");
  const std::string name = arg.substr(0, eq), level_text = arg.substr(eq + 1);
  std::string bounding;
  Material* material = nullptr;
  for (Material& m : desc.materials) {
    if (m.priority != kPriorityOff) bounding += (bounding.empty() ? "" : ", ") + m.name;
    if (m.name == name) material = &m;
  }
  const std::string known = bounding.empty() ? "the scene has none" : "they are: " + bounding;
  if (!material || material->priority == kPriorityOff)
    throw InputError(kCommandLine, "--priority: \"" + name + "\" is not a material that bounds a medium (" +
                                       known + ")");
  std::optional<int> level = priority_from_name(level_text);
  if (!level && !level_text.empty() && level_text.find_first_not_of("0123456789") == std::string::npos &&
      level_text.size() <= 6 && std::stoi(level_text) <= kMaxPriority)
    level = std::stoi(level_text);
  if (!level)
    throw InputError(kCommandLine, "--priority " + arg + ": expected a level (" + priority_names() +
                                       " or an integer in [0, " + std::to_string(kMaxPriority) + "])");
  if (*level == kPriorityOff && material->interior >= 0)
    throw InputError(kCommandLine, "--priority " + arg + ": material \"" + name +
                                       "\" has an interior medium, so its priority cannot be off");
  material->priority = *level;
}

int list_builtins() {
  for (const BuiltinScene& b : builtin_scenes())
    std::printf("%-18s %s\n", b.name.c_str(), b.description.c_str());
  return 0;
}

}  // namespace

int run_render(const RenderOptions& o) {
  if (o.list_builtins) return list_builtins();
  if (!(o.time >= 0.0f && o.time <= 1e6f)) throw InputError(kCommandLine, "--time: expected seconds in [0, 1e6]");
  SceneDesc desc = load_scene(o.scene).at_time(o.time);
  for (const std::string& p : o.priorities) apply_priority(p, desc);
  const RenderSettings settings = settings_from(o, desc);
  const std::filesystem::path exr = o.output.empty() ? default_output(o.scene) : o.output;
  check_output(exr);
  const auto scene = Scene::build(desc);

  const RenderResult result =
      render(*scene, settings, o.quiet ? Progress::Style::kQuiet : Progress::Style::kAuto);
  std::filesystem::path png = exr;
  png.replace_extension(".png");
  write_exr(exr.string(), result.image);
  write_png(png.string(), result.image.width(), result.image.height(),
            to_srgb8_preview(result.image, PreviewSettings{o.exposure, true}));
  if (!o.quiet) print_summary(o.scene, settings, result.stats, exr.string());
  return 0;
}

}  // namespace caligo
