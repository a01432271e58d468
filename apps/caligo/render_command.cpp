// caligo render [SCENE.json | BUILTIN] [-o out.exr] [--spp N] [--res WxH] [--threads N] [--seed S]
//               [--priority MATERIAL=LEVEL ...] [--light-sampler tree|power|uniform|tree-fixed-share] [--aov LIST]
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <optional>
#include <string>

#include "checkpoint.h"
#include "commands.h"
#include "core/error.h"
#include "distributed/frame.h"
#include "interrupt.h"
#include "render/progressive.h"
#include "render/render.h"
#include "render_denoised.h"
#include "preview_server.h"
#include "render_metadata.h"
#include "render_outputs.h"
#include "scene/builtins.h"
#include "scene/material_priority.h"
#include "scene/scene_parser.h"
#include "scene/scene_warnings.h"

namespace caligo {

namespace {

// The value an option names, or an error that lists the names (the user's text made printable).
template <class E, size_t N>
E parse_choice(const char* option, const std::string& text, const std::array<EnumName<E>, N>& names) {
  if (const std::optional<E> value = enum_from_name(names, text)) return *value;
  throw InputError(kCommandLine, std::string(option) + ": expected " + enum_choices(names) + ", got \"" +
                                     printable_for_message(text) + "\"");
}

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
  if (o.distance_sampling) path.distance_sampling = parse_choice("--distance-sampling", *o.distance_sampling, kDistanceSamplingNames);
  if (o.secondary) path.secondary = parse_choice("--secondary", *o.secondary, kSecondarySegmentsNames);
  if (o.deferred_nee) {
    if (*o.deferred_nee < 0 || *o.deferred_nee > 64)
      throw InputError(kCommandLine, "--deferred-nee: expected 0 to 64, got " + std::to_string(*o.deferred_nee));
    path.deferred_nee = *o.deferred_nee;
  }
  if (o.light_sampler) path.light_sampler = parse_choice("--light-sampler", *o.light_sampler, kLightSamplerNames);
  if (o.guiding) path.guiding = parse_choice("--guiding", *o.guiding, kGuidingModeNames);
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
    const PixelFilterType type = parse_choice("--filter", *o.filter, kPixelFilterNames);
    s.filter = {type, PixelFilterDesc::default_radius(type), PixelFilterDesc{}.sigma};
  }
  if (o.crop) s.crop = parse_crop(*o.crop);
  if (o.aovs) {
    try {
      s.aovs = AovSet::parse(*o.aovs);
    } catch (const InputError& e) {
      throw InputError(kCommandLine, e.what());
    }
  }
  if (s.crop.pixels(s.resolution).empty()) {
    const SourceLocation where = o.crop ? kCommandLine : SourceLocation{desc.file, "/render/crop"};
    throw InputError(where, "the crop window holds no pixel at " + std::to_string(s.resolution.x) + "x" +
                                std::to_string(s.resolution.y));
  }
}

// --adaptive-threshold, --adaptive-min-samples, --clamp-direct and --clamp-indirect.
void apply_sampling_options(const RenderOptions& o, RenderSettings& s) {
  if (o.adaptive_threshold) {
    if (!(*o.adaptive_threshold > 0.0f && *o.adaptive_threshold <= 1.0f))
      throw InputError(kCommandLine, "--adaptive-threshold: expected a relative error in (0, 1], e.g. 0.01");
    s.adaptive.threshold = *o.adaptive_threshold;
  }
  if (o.adaptive_min_samples) {
    if (*o.adaptive_min_samples < 1 || *o.adaptive_min_samples > 1'000'000)
      throw InputError(kCommandLine, "--adaptive-min-samples: expected 1 to 1000000");
    if (!(s.adaptive.threshold > 0.0f)) throw InputError(kCommandLine, "--adaptive-min-samples needs --adaptive-threshold");
    s.adaptive.min_samples = *o.adaptive_min_samples;
  }
  if (s.adaptive.threshold > 0.0f) s.aovs = s.aovs.with(Aov::kVariance);
  const auto limit = [](std::optional<float> v, const char* option, float& out) {
    if (!v) return;
    if (!(std::isfinite(*v) && *v >= 0.0f)) throw InputError(kCommandLine, std::string(option) + ": expected a value >= 0");
    out = *v;
  };
  limit(o.clamp_direct, "--clamp-direct", s.clamp.direct);
  limit(o.clamp_indirect, "--clamp-indirect", s.clamp.indirect);
}

// The scene's settings with every option of the command line applied.
RenderSettings settings_from(const RenderOptions& o, const SceneDesc& desc) {
  RenderSettings s = render_settings(desc);
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
  if (o.seed) s.seed = parse_seed(*o.seed);
  apply_path_options(o, s.path);
  apply_image_options(o, desc, s);
  apply_sampling_options(o, s);
  return s;
}

// `samples`: the fewest and most samples a pixel of the image holds (a time limit, an error
// target or a resume make them differ from --spp).
void print_summary(const std::string& scene, const RenderSettings& s, const RenderStats& stats,
                   const std::string& output, std::pair<int, int> samples) {
  const std::string spp = samples.first == samples.second
                              ? std::to_string(samples.first)
                              : std::to_string(samples.first) + " to " + std::to_string(samples.second);
  std::fprintf(stderr, "caligo: %s %dx%d, %s spp: %s wall, %.3g paths/s, %.3g rays/s, %d threads -> %s\n",
               scene.c_str(), s.resolution.x, s.resolution.y, spp.c_str(), format_duration(stats.seconds).c_str(),
               double(stats.paths) / stats.seconds, double(stats.rays) / stats.seconds,
               s.threads > 0 ? s.threads : int(std::thread::hardware_concurrency()), output.c_str());
  if (stats.guiding.leaves > 0)
    std::fprintf(stderr, "caligo: guiding: %d of %d training iterations, %llu spatial leaves, %llu directional nodes, %.3g MB\n",
                 stats.guiding.iterations, GuidingConfig{}.iterations, (unsigned long long)stats.guiding.leaves,
                 (unsigned long long)stats.guiding.nodes, double(stats.guiding.bytes) / 1e6);
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

int list_builtins() { return run_scene(SceneCommandOptions{}); }

ProgressiveSchedule schedule_from(const RenderOptions& o) {
  ProgressiveSchedule p;
  const auto duration = [](const std::optional<std::string>& text, const char* flag) -> std::optional<double> {
    if (!text) return std::nullopt;
    const auto seconds = parse_duration(*text);
    if (!seconds)
      throw InputError(kCommandLine, std::string(flag) + ": expected a positive duration such as 90, 90s, 5m or 2h, got " +
                                         quote_for_message(*text));
    return seconds;
  };
  p.time_limit = duration(o.time_limit, "--time-limit");
  p.refine = !o.single_pass;
  if (o.checkpoint_every && !o.checkpoint) throw InputError(kCommandLine, "--checkpoint-every needs --checkpoint FILE");
  if (o.checkpoint) p.checkpoint_every = o.checkpoint_every ? duration(o.checkpoint_every, "--checkpoint-every") : 60.0;
  if (o.target_rmse) {
    if (!std::isfinite(*o.target_rmse) || !(*o.target_rmse > 0.0))
      throw InputError(kCommandLine, "--target-rmse: expected a positive finite number");
    p.target_rmse = *o.target_rmse;
  }
  return p;
}

// The memory this machine can still give (MemAvailable), or nullopt where it cannot be read.
std::optional<uint64_t> available_memory() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  uint64_t kib = 0;
  std::string unit;
  while (meminfo >> key >> kib >> unit)
    if (key == "MemAvailable:") return kib * 1024;
  return std::nullopt;
}

// A render whose film would not fit in the machine's memory is refused before it starts.
void check_memory(const RenderSettings& s) {
  const uint64_t need = Film::memory_estimate(s.resolution, s.aovs);
  const auto have = available_memory();
  if (have && need > *have)
    throw EnvironmentError("the film of a " + std::to_string(s.resolution.x) + "x" + std::to_string(s.resolution.y) +
                           " render with these outputs needs about " + std::to_string(need >> 20) +
                           " MiB, but only " + std::to_string(*have >> 20) +
                           " MiB of memory are available (use fewer --aov layers, a smaller --res or --crop)");
}

// A checkpoint to resume: its film must be this render's (key, resolution, outputs).
Film load_checkpoint(const std::string& path, uint64_t key, const RenderSettings& s) {
  uint64_t saved_key = 0;
  Film film = Film::load(path, &saved_key);
  const SourceLocation where{path, ""};
  if (saved_key != key)
    throw InputError(where, "this checkpoint is of another scene or other settings (scene text, resolution, "
                            "seed, path, filter, crop, outputs, time or priorities differ); it cannot be resumed here");
  if (film.resolution() != s.resolution || film.aovs() != s.aovs)
    throw InputError(where, "this checkpoint's resolution or outputs differ from the render's");
  // A guided render's field is read here, so that a damaged one is refused naming the file.
  if (!film.training_state().empty()) {
    if (!guided(s)) throw InputError(where, "this checkpoint holds a guiding field, but the render is not guided");
    (void)GuidingField::from_bytes(film.training_state(), path);
  }
  return film;
}



// The passes' progress line and the checkpoints between them.
ProgressiveHooks progress_hooks(const RenderOptions& o, const RenderOutputs& outputs, uint64_t key, const Film& film,
                                PreviewServer* preview) {
  ProgressiveHooks hooks;
  // A line per pass where passes are what was asked for; plain refinement shows the progress bar.
  if (!o.quiet && (o.checkpoint || o.time_limit || o.target_rmse))
    hooks.on_pass = [](int done, int target, double seconds) {
      std::fprintf(stderr, "caligo: %d of %d samples per pixel (%s)\n", done, target, format_duration(seconds).c_str());
    };
  // Between passes no render thread writes the film: the page gets it resolved.
  if (preview)
    hooks.on_pass = [preview, &film, log = hooks.on_pass](int done, int target, double seconds) {
      if (log) log(done, target, seconds);
      preview->publish({film.resolve(), done, target, seconds, false, {}});
    };
  hooks.save_checkpoint = [&outputs, key](const Film& film) { film.save(outputs.checkpoint(), key); };
  // A checkpoint that fails (a full disk for a moment) must not end a long render: the film is
  // still in memory, and the next checkpoint or the end tries again.
  hooks.on_checkpoint_failed = [](const std::exception& e) {
    std::fprintf(stderr, "caligo: warning: checkpoint not saved, the render goes on: %s\n",
                 printable_for_message(e.what()).c_str());
  };
  return hooks;
}

// The interrupted render's outputs are written; says what they are and how to continue.
int report_interrupt(const RenderOutputs& outputs, int signal, std::pair<int, int> samples, int target) {
  const std::string exr = quote_for_message(outputs.partial_exr()), ckpt = quote_for_message(outputs.checkpoint()),
                    kept = quote_for_message(outputs.exr());
  if (outputs.interrupt_leaves_checkpoint())
    std::fprintf(stderr,
                 "caligo: interrupted (signal %d) with %d to %d of %d samples per pixel: wrote the partial image %s "
                 "(%s, if it exists, is kept) and the checkpoint %s; continue with --resume %s\n",
                 signal, samples.first, samples.second, target, exr.c_str(), kept.c_str(), ckpt.c_str(), ckpt.c_str());
  else
    std::fprintf(stderr,
                 "caligo: interrupted (signal %d) with %d to %d of %d samples per pixel: wrote the partial image %s "
                 "(%s, if it exists, is kept); no checkpoint (%s cannot be written; give --checkpoint FILE)\n",
                 signal, samples.first, samples.second, target, exr.c_str(), kept.c_str(), ckpt.c_str());
  return kExitInterruptedBase + signal;
}

// What the EXR header records of this render (render_metadata.h).
ExrAttributes header_of(const SceneDesc& desc, const RenderSettings& s, std::pair<int, int> samples, double seconds) {
  return render_attributes({desc.file, s.seed, samples, seconds}, Camera(desc.camera, s.resolution));
}

// Under mpirun/srun each rank renders its share and rank 0 alone gets the frame (src/distributed/).
int run_distributed(const RenderOptions& o, const SceneDesc& desc, const ProgressiveSchedule& schedule, const Scene& scene,
                    const RenderSettings& settings, const RenderOutputs& outputs, uint64_t key,
                    Progress::Style style) {
  if (settings.adaptive.threshold > 0.0f && o.mpi_split == "samples")
    throw InputError(kCommandLine, "adaptive sampling stops each pixel by its own samples, which --mpi-split samples "
                                   "spreads over the ranks: use --mpi-split rows");
  if (o.checkpoint || o.resume || schedule.time_limit || schedule.target_rmse)
    throw InputError(kCommandLine, "--checkpoint, --resume, --time-limit and --target-rmse are for single-process "
                                   "renders, not under mpirun");
  const std::optional<RenderResult> frame =
      distributed::render_frame(scene, settings, *distributed::split_from_name(o.mpi_split), style, key);
  if (!frame) return 0;  // an MPI rank other than 0: rank 0 writes the outputs
  outputs.write_final(frame->image, nullptr, key,
                      header_of(desc, settings, {settings.spp, settings.spp}, frame->stats.seconds));
  if (!o.quiet) print_summary(o.scene, settings, frame->stats, outputs.exr(), {settings.spp, settings.spp});
  return 0;
}

// The outputs of a single-process render that has ended: the final image (and the asked-for
// checkpoint), or the partial image when it was interrupted or stopped before every pixel had a
// sample; the preview page gets the last state first. `resume_key` gives the checkpoint key an
// interrupt's checkpoint takes: called only then, as it may re-read every asset of the scene.
int write_render(const RenderOptions& o, const SceneDesc& desc, const RenderSettings& settings,
                 const RenderOutputs& outputs, const Film& film, const ProgressiveResult& result,
                 const InterruptGuard& interrupt, PreviewServer* preview,
                 const std::function<uint64_t()>& resume_key, uint64_t key) {
  const Image image = film.resolve();
  const int target = settings.spp;
  const auto samples = sample_range(film, settings);
  if (preview) {
    preview->publish({image, samples.first, target, result.stats.seconds, true, {}});
    preview->linger(2.0);
  }
  if (samples.second > target && !o.quiet)
    std::fprintf(stderr, "caligo: the checkpoint already held %d samples per pixel, more than --spp %d: all are kept\n",
                 samples.second, target);
  // A signal after the last sample changes nothing: the render is complete. A time limit that
  // cut the first pass leaves pixels without a sample: that image must not replace a finished one.
  const bool complete = samples.first >= target || (!result.stopped_by.empty() && samples.first > 0);
  if (interrupt.stopped() && !complete) {
    outputs.write_interrupted(image, film, resume_key(), header_of(desc, settings, samples, result.stats.seconds));
    return report_interrupt(outputs, interrupt.signal_number(), samples, target);
  }
  if (!complete && !result.stopped_by.empty()) {
    outputs.write_interrupted(image, film, resume_key(), header_of(desc, settings, samples, result.stats.seconds));
    std::fprintf(stderr, "caligo: %s came before every pixel had a sample: wrote the partial image %s (%s is kept)\n",
                 result.stopped_by.c_str(), quote_for_message(outputs.partial_exr()).c_str(),
                 quote_for_message(outputs.exr()).c_str());
    return 0;
  }
  outputs.write_final(image, &film, key, header_of(desc, settings, samples, result.stats.seconds));
  if (!result.stopped_by.empty() && !o.quiet)
    std::fprintf(stderr, "caligo: stopped by %s at %d of %d samples per pixel\n", result.stopped_by.c_str(),
                 samples.first, target);
  if (!o.quiet) print_summary(o.scene, settings, result.stats, outputs.exr(), samples);
  return 0;
}

}  // namespace

int run_render(const RenderOptions& o) {
  if (o.list_builtins) return list_builtins();
  if (o.frames) return run_render_sequence(o);
  // From here on the first SIGINT/SIGTERM asks for a stop (a checkpoint and a partial image,
  // empty if it comes before the render), a second quits.
  const InterruptGuard interrupt;
  if (!(o.time >= 0.0f && o.time <= 1e6f)) throw InputError(kCommandLine, "--time: expected seconds in [0, 1e6]");
  SceneDesc desc = load_scene(o.scene, o.frame).at_time(o.time);
  for (const std::string& p : o.priorities) apply_priority(p, desc);
  RenderSettings settings = settings_from(o, desc);
  const ProgressiveSchedule schedule = schedule_from(o);
  if (schedule.target_rmse) settings.aovs = settings.aovs.with(Aov::kVariance);
  if (!(std::isfinite(o.exposure) && std::abs(o.exposure) <= 64.0f))
    throw InputError(kCommandLine, "--exposure: expected stops in [-64, 64]");
  const RenderOutputs outputs(o, desc);  // every output is checked before any work
  check_memory(settings);
  const auto scene = Scene::build(desc);  // meshes load here: their errors come first, located
  print_scene_warnings(desc);
  for (const std::string& w : priority_shadow_warnings(desc)) std::fprintf(stderr, "caligo: warning: %s\n", w.c_str());
  // The key re-reads every file the scene names (for their CRC-32s): only when a checkpoint is
  // read, saved or shared between ranks; an interrupt's own checkpoint takes it then.
  const auto key_now = [&] { return checkpoint_key(scene_source(o.scene), desc.files, settings, o.time, o.priorities); };
  const bool keyed = o.checkpoint || o.resume || distributed::launcher_world_size();
  const uint64_t key = keyed ? key_now() : 0;
  const Progress::Style style = o.quiet ? Progress::Style::kQuiet : Progress::Style::kAuto;
  if (distributed::launcher_world_size()) {
    if (o.preview) throw InputError(kCommandLine, "--preview is for single-process renders, not under mpirun");
    return run_distributed(o, desc, schedule, *scene, settings, outputs, key, style);
  }
  const std::unique_ptr<PreviewServer> preview =
      start_preview(o.preview, [&interrupt] { interrupt.request_stop(); }, o.view == "filmic");
  if (o.denoise)
    return run_render_denoised(o, *scene, settings, outputs, [&](std::pair<int, int> samples, double seconds) {
      return header_of(desc, settings, samples, seconds);
    }, preview.get(), interrupt);

  Film film = o.resume ? load_checkpoint(*o.resume, key, settings) : Film(settings.resolution, settings.aovs);
  const ProgressiveResult result =
      render_progressive(film, *scene, settings, schedule, progress_hooks(o, outputs, key, film, preview.get()),
                         &interrupt.stop(), style);
  return write_render(o, desc, settings, outputs, film, result, interrupt, preview.get(),
                      [&] { return keyed ? key : key_now(); }, key);
}

}  // namespace caligo
