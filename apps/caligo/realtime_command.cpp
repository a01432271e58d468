// caligo realtime SCENE [--frames N] [--res WxH] [--scale full|half|quarter]
//                 [--method march|none|brute|hybrid|textured] [-o OUT] ...
// Renders the scene's camera path with the real-time pipeline, prints the per-pass table
// (median over the frames after warm-up) and optionally compares the last frame with the
// path tracer's single-scattering reference.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "commands.h"
#include "denoise/denoise_layers.h"
#include "preview_server.h"
#include "realtime_outputs.h"
#include "core/median.h"
#include "core/message_text.h"
#include "hybrid/hybrid_pipeline.h"
#include "realtime/frame_light.h"
#include "realtime/pipeline.h"
#include "realtime/reference_compare.h"
#include "render/render.h"
#include "scene/scene.h"

namespace caligo {

void add_realtime_command(CLI::App& app, RealtimeOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "realtime", "Render the scene's camera path with the real-time volumetric lighting pipeline");
  cmd->add_option("scene", o.scene, "Scene file (.json) or built-in name");
  cmd->add_option("-o,--output", o.output,
                  "A folder for the frames (frame_0000.png, ...), a .gif for an animation, or a .png/.exr "
                  "for the last frame only");
  cmd->add_option("--frames", o.frames, "Frames to render (overrides the scene's realtime.frames)");
  cmd->add_option("--res", o.resolution, "Output resolution WxH (overrides the scene)");
  cmd->add_option("--scale", o.scale, "Accumulation resolution: full, half or quarter");
  cmd->add_option("--method", o.method,
                  "Volumetric method: march (ray marching with shadow maps per light, all lights), froxel (every "
                  "light and medium in one camera-aligned froxel grid); of point lights in one homogeneous medium: "
                  "none (airlight, no volumetric shadows), brute (150 steps, closed-form lit "
                  "intervals), hybrid (Wyman & Ramsey shadow volumes, 50 steps) or textured (hybrid, and spot lights by "
                  "the textured-spotlight march); other lights march");
  cmd->add_option("--froxels", o.froxels,
                  "--method froxel: the grid's columns and depth slices, WxHxD (default: a column per 12x12 "
                  "pixels and 64 slices, 160x90x64 at 1920x1080)");
  cmd->add_option("--spot-model", o.spot_model,
                  "Per-step in-scattering of --method textured spots: auto (airlight for a grey isotropic medium, "
                  "else Hoffman-Preetham), airlight (Sun et al.; isotropic only, a pass per channel of a coloured "
                  "medium) or hoffman-preetham (any phase, one pass)");
  cmd->add_option("--scene-buffers", o.scene_buffers, "Depth/normal buffers by: raster (default) or embree");
  cmd->add_option("--samples", o.samples, "March steps per pixel per light");
  cmd->add_option("--tile", o.tile_size, "Interleaved-sampling tile side (1: no interleaving)");
  cmd->add_option("--gather-radius", o.gather_radius, "Bilateral gather taps each side for marched lights (0: no gather)");
  cmd->add_option("--scatter-gather-radius", o.scatter_gather_radius,
                  "Bilateral gather taps each side for lights of --method none|brute|hybrid|textured (default 1: 3x3)");
  cmd->add_option("--steps", o.steps, "March steps of point and spot lights: uniform (the seed) or equiangular");
  cmd->add_option("--ms-floor", o.ms_floor, "Faked multiple scattering: minimum shadow term in [0, 1]");
  cmd->add_option("--temporal", o.temporal, "Temporal reprojection on or off (true/false)");
  cmd->add_option("--light-cores", o.light_cores,
                  "Re-march the pixels around on-screen point lights and spot apexes at full resolution (true) or "
                  "leave them to the upsampled buffer (false, the default: the pass is slow)");
  cmd->add_option("--warmup", o.warmup, "Frames left out of the timing medians");
  cmd->add_option("--time", o.still_time,
                  "Render every frame at this time in seconds (a still scene: only the interleaving changes)");
  cmd->add_flag("--exr", o.exr, "Write OpenEXR frames instead of PNG");
  cmd->add_flag("--scalar", o.scalar, "Use the scalar passes instead of the SIMD ones");
  cmd->add_flag("--compare-reference", o.compare_reference,
                "Also path-trace the last frame (single scattering, direct light) and compare");
  cmd->add_option("--reference-spp", o.reference_spp, "Samples per pixel of the reference");
  cmd->add_flag("--reference-per-light", o.reference_per_light,
                "Path-trace the reference one light at a time and sum (far less noise with many lights)");
  cmd->add_option("--exposure", o.exposure, "Exposure of the PNG/GIF output, in stops");
  cmd->add_option("--preview", o.preview,
                  "Stream the frames and the pass table to a page on 127.0.0.1 (PORT, or any free port); the URL, with "
                  "its access token, is printed")
      ->expected(0, 1);
  cmd->add_option("--view", o.view,
                  "Tone curve of the PNG/GIF output: filmic (the ACES fit, default) or standard (sRGB, clipped at 1)")
      ->check(CLI::IsMember({"filmic", "standard"}));
  cmd->add_flag("-q,--quiet", o.quiet, "Print only the summary line");
}

namespace {

std::optional<SpotScatterModel> spot_model_of(const std::string& name) {
  if (name == "auto") return SpotScatterModel::kAuto;
  if (name == "airlight") return SpotScatterModel::kAirlight;
  if (name == "hoffman-preetham") return SpotScatterModel::kHoffmanPreetham;
  return std::nullopt;
}

int check_int(std::optional<int> v, int lo, int hi, const char* option, int fallback) {
  if (!v) return fallback;
  if (*v < lo || *v > hi)
    throw InputError(kCommandLine, std::string(option) + ": expected " + std::to_string(lo) + " to " +
                                       std::to_string(hi) + ", got " + std::to_string(*v));
  return *v;
}

// --froxels WxHxD: 1 to 1024 columns each way and 2 to 512 slices (a 512^3 grid would hold
// 3 GB: the product is held to 2^26 froxels).
FroxelSettings parse_froxels(const std::string& text, FroxelSettings s) {
  int w = 0, h = 0, d = 0;
  char x1 = 0, x2 = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c%d%c", &w, &x1, &h, &x2, &d, &extra) != 5 || x1 != 'x' || x2 != 'x')
    throw InputError(kCommandLine, "--froxels: expected WxHxD such as 160x90x64, got " + quote_for_message(text));
  if (w < 1 || h < 1 || w > 1024 || h > 1024 || d < 2 || d > 512 ||
      uint64_t(w) * uint64_t(h) * uint64_t(d) > (uint64_t(1) << 26))
    throw InputError(kCommandLine, "--froxels: expected 1 to 1024 columns each way, 2 to 512 slices and at most "
                                   "2^26 froxels, got " + quote_for_message(text));
  s.width = w;
  s.height = h;
  s.slices = d;
  return s;
}

RealtimeSettings settings_from(const RealtimeOptions& o, const SceneDesc& desc) {
  RealtimeSettings s = realtime_settings(desc);
  if (o.resolution) s.resolution = parse_resolution(*o.resolution);
  if (uint64_t(s.resolution.x) * uint64_t(s.resolution.y) > (uint64_t(1) << 26))
    throw InputError(kCommandLine, "resolution has more than 2^26 pixels");
  if (o.scale) {
    if (*o.scale == "full") s.scale = 1;
    else if (*o.scale == "half") s.scale = 2;
    else if (*o.scale == "quarter") s.scale = 4;
    else throw InputError(kCommandLine, "--scale: expected full, half or quarter, got \"" + *o.scale + "\"");
  }
  s.froxel = o.method == "froxel";
  if (!s.froxel && !parse_volumetric_method(o.method))
    throw InputError(kCommandLine,
                     "--method: expected march, froxel, none, brute, hybrid or textured, got \"" + o.method + "\"");
  if (o.froxels) {
    s.froxels = parse_froxels(*o.froxels, s.froxels);
    if (!s.froxel)
      std::fprintf(stderr, "caligo: warning: --froxels sets the grid of --method froxel; with --method %s it is "
                           "not used\n",
                   o.method.c_str());
  }
  if (!spot_model_of(o.spot_model))
    throw InputError(kCommandLine,
                     "--spot-model: expected auto, airlight or hoffman-preetham, got \"" + o.spot_model + "\"");
  if (o.scene_buffers == "raster") s.scene_buffers = SceneBufferMethod::raster;
  else if (o.scene_buffers == "embree") s.scene_buffers = SceneBufferMethod::embree;
  else throw InputError(kCommandLine, "--scene-buffers: expected raster or embree, got \"" + o.scene_buffers + "\"");
  s.accumulation.samples = check_int(o.samples, 1, 1024, "--samples", s.accumulation.samples);
  s.accumulation.tile_size = check_int(o.tile_size, 1, 32, "--tile", s.accumulation.tile_size);
  s.gather_radius = check_int(o.gather_radius, 0, 16, "--gather-radius", s.gather_radius);
  s.scatter_gather_radius =
      check_int(o.scatter_gather_radius, 0, 16, "--scatter-gather-radius", s.scatter_gather_radius);
  if (o.ms_floor) {
    if (!(*o.ms_floor >= 0.0f && *o.ms_floor <= 1.0f))
      throw InputError(kCommandLine, "--ms-floor: expected a number in [0, 1]");
    s.accumulation.multiple_scattering_floor = *o.ms_floor;
  }
  if (o.temporal) s.temporal = *o.temporal;
  if (o.light_cores) s.resolve_light_cores = *o.light_cores;
  if (o.steps) {
    if (*o.steps != "uniform" && *o.steps != "equiangular")
      throw InputError(kCommandLine, "--steps: expected uniform or equiangular, got \"" + *o.steps + "\"");
    s.accumulation.equiangular = *o.steps == "equiangular";
  }
  s.simd = !o.scalar;
  return s;
}

std::string light_kind(const Light& light) {
  const auto* spot = std::get_if<SpotLight>(&light);
  return std::string(light_type_name(light)) + (spot && spot->gobo.image ? "+gobo" : "");
}

// What stands in for a light the passes do not shade as it is ("" for the others): "point"
// for an area light, "N suns" for the environment (realtime/light_stand_ins.h).
std::string stand_in_name(const Light& light, const RealtimeSettings& settings) {
  if (std::holds_alternative<EnvironmentLight>(light))
    return std::to_string(shaded_lights(light, settings.environment_lights).size()) + " suns";
  const auto one = shaded_light(light);
  if (!one) return "";
  const bool same = std::visit([&](const auto& l) { return std::holds_alternative<std::decay_t<decltype(l)>>(light); }, *one);
  return same ? "" : std::string(std::visit([](const auto& l) { return l.kTypeName; }, *one));
}

// "not shaded" (a light type the passes leave to the path tracer), "froxel", "march", or what
// the scatterer used for the light in the last frame; ", as <stand-in>" for a stand-in.
std::string light_method(const SceneDesc& desc, const RealtimeSettings& settings, const HybridScatterer* scatterer,
                         size_t light) {
  if (!is_shaded(desc.lights[light])) return "not shaded";
  const std::string as = stand_in_name(desc.lights[light], settings);
  const std::string method =
      settings.froxel ? "froxel" : volumetric_method_name(scatterer ? scatterer->used(light) : VolumetricMethod::kMarch);
  return as.empty() ? method : method + " as " + as;
}

void print_table(const SceneDesc& desc, const RealtimeSettings& settings, const std::vector<PassTimes>& timed,
                 const HybridScatterer* scatterer) {
  const auto row = [&](const char* name, auto get) {
    std::vector<double> v;
    for (const PassTimes& t : timed) v.push_back(get(t));
    std::printf("  %-40s %10.0f\n", name, median(v));
  };
  std::printf("pass (median over %zu frames)                     us\n", timed.size());
  row("depth + normals", [](const PassTimes& t) { return t.depth; });
  row("shadow maps", [](const PassTimes& t) { return t.shadows; });
  row("accumulation", [](const PassTimes& t) { return t.accumulation; });
  row("  camera rays (all lights)", [](const PassTimes& t) { return t.rays; });
  for (size_t i = 0; i < desc.lights.size(); ++i) {
    if (!desc.options(i).volumetric) continue;
    char name[64];
    std::snprintf(name, sizeof name, "  light %zu (%s, %s)", i, light_kind(desc.lights[i]).c_str(),
                  light_method(desc, settings, scatterer, i).c_str());
    row(name, [i](const PassTimes& t) { return i < t.per_light.size() ? t.per_light[i] : 0.0; });
  }
  row("gather", [](const PassTimes& t) { return t.gather; });
  row("upsample", [](const PassTimes& t) { return t.upsample; });
  row("temporal", [](const PassTimes& t) { return t.temporal; });
  row("surfaces", [](const PassTimes& t) { return t.surfaces; });
  row("composite", [](const PassTimes& t) { return t.composite; });
  row("total", [](const PassTimes& t) { return t.total; });
  row("volumetric (acc+gat+up+tmp)", [](const PassTimes& t) { return t.volumetric(); });
}

// Frame-to-frame change of the volumetric light: mean |v_i - v_{i-1}| / mean v_i over pixels
// and channels. For a still scene it is pure flicker (interleaving noise the gather and the
// history did not remove); for a moving camera it also holds real change.
double frame_change(const ColorPlanes& a, const ColorPlanes& b) {
  double diff = 0, sum = 0;
  for (const auto& [pa, pb] : {std::pair{&a.r, &b.r}, std::pair{&a.g, &b.g}, std::pair{&a.b, &b.b}})
    for (size_t i = 0; i < pa->data.size(); ++i) {
      diff += std::abs(double(pa->data[i]) - double(pb->data[i]));
      sum += double(pa->data[i]);
    }
  return sum > 0 ? diff / sum : 0.0;
}

// Light that is not from the scene's lights: emissive materials and media would be counted
// once per light by a per-light reference.
bool has_other_emitters(const SceneDesc& desc) {
  for (const Material& m : desc.materials)
    if (!m.emission.is_black()) return true;
  for (const VolumePrimitive& v : desc.volumes)
    if (!v.shader.emission.is_black()) return true;
  return false;
}

// The path tracer's single-scattering, direct-light render of the still scene. Per light:
// one render per light, summed (single scattering and direct light are linear in the lights),
// so that no light is sampled with a small selection probability: with one power-weighted
// light choice per vertex, a scene whose sun outshines its spots picks each spot rarely and
// the reference fills with fireflies.
Image reference_image(const RealtimeOptions& o, const SceneDesc& still, Vec2i resolution) {
  RenderSettings rs = render_settings(still);
  rs.resolution = resolution;
  rs.spp = o.reference_spp;
  rs.path.limits.max_bounces = 1;
  rs.path.limits.max_volume_bounces = 1;
  const auto style = o.quiet ? Progress::Style::kQuiet : Progress::Style::kAuto;
  if (!o.reference_per_light || still.lights.size() < 2) return render(*Scene::build(still), rs, style).image;
  Image sum;
  for (size_t i = 0; i < still.lights.size(); ++i) {
    SceneDesc one = still;
    one.lights = {still.lights[i]};
    one.light_options = {still.options(i)};
    const Image image = render(*Scene::build(one), rs, style).image;
    if (i == 0) {
      sum = image;
      continue;
    }
    const auto c = *sum.rgb_indices();  // the film always writes R, G, B; other AOVs stay light 0's
    for (int y = 0; y < sum.height(); ++y)
      for (int x = 0; x < sum.width(); ++x)
        for (int k : c) sum.at(x, y, k) += image.at(x, y, k);
  }
  return sum;
}

void compare_with_reference(const RealtimeOptions& o, const SceneDesc& desc, const RealtimeSettings& s, float time,
                            const RealtimeFrame& frame, RealtimeOutputs& outputs) {
  const Image reference = reference_image(o, desc.at_time(time), s.resolution);
  const Image realtime = to_image(frame.color);
  const std::vector<uint8_t> cores =
      light_core_mask(desc.lights_at(time), frame.view, kLightCoreRadius * float(s.scale));
  const ReferenceError err = reference_error(realtime, reference, &cores);
  std::printf("reference (%d spp%s, single scattering, direct light): mean error %+.2f %%, relative RMSE %.2f %%, "
              "RMSE/mean %.2f %%\n",
              o.reference_spp, o.reference_per_light ? " per light" : "", err.mean_error * 100.0,
              err.relative_rmse * 100.0, err.rmse_over_mean * 100.0);
  std::printf("  outside the light cores (%.2f %% of the pixels within %.0f px of a light): RMSE/mean %.2f %%; "
              "in them: mean error %+.2f %%\n",
              err.core_fraction * 100.0, kLightCoreRadius * float(s.scale), err.outside_rmse_over_mean * 100.0,
              err.core_mean_error * 100.0);
  std::printf("  where the reference is dark (below 1 %% of its mean: %.2f %% of the pixels): %.3f %% of the "
              "real-time frame's light\n",
              err.dark_fraction * 100.0, err.dark_share * 100.0);
  const Rgb8Image strip = comparison_strip(realtime, reference, o.exposure, 0.5f);
  outputs.comparison(strip.width, strip.height, strip.rgb);
  std::printf("comparison (real-time | reference | |error| / mean, 0..50 %%) -> %s\n", outputs.comparison_path().c_str());
}

// The options run_realtime checks itself (the scene's own values are checked by its parser).
void check_realtime_options(const RealtimeOptions& o, const SceneDesc& desc) {
  if (o.warmup < 0) throw InputError(kCommandLine, "--warmup: expected 0 or more");
  if (!(o.reference_spp >= 1 && o.reference_spp <= 1'000'000))
    throw InputError(kCommandLine, "--reference-spp: expected 1 to 1000000");
  if (!(std::isfinite(o.exposure) && std::abs(o.exposure) <= 64.0f))
    throw InputError(kCommandLine, "--exposure: expected stops in [-64, 64]");
  if (o.still_time && !(*o.still_time >= 0.0f && *o.still_time <= 1e6f))
    throw InputError(kCommandLine, "--time: expected seconds in [0, 1e6]");
  if (o.reference_per_light && has_other_emitters(desc))
    throw InputError(kCommandLine,
                     "--reference-per-light: the scene has emissive materials or media, whose light a per-light "
                     "reference would count once per light");
}

// The one-line summary, the method per light and the frame-to-frame change.
void print_summary(const RealtimeOptions& o, const SceneDesc& desc, const RealtimeSettings& settings, int frames,
                   const std::vector<PassTimes>& timed, const HybridScatterer* scatterer,
                   const std::vector<double>& changes) {
  std::vector<double> volumetric, total;
  for (const PassTimes& t : timed) {
    volumetric.push_back(t.volumetric());
    total.push_back(t.total);
  }
  const Vec2i low{(settings.resolution.x + settings.scale - 1) / settings.scale,
                  (settings.resolution.y + settings.scale - 1) / settings.scale};
  std::printf("caligo realtime: %s %dx%d, accumulation %dx%d, %zu lights, %d frames: volumetric %.2f ms, "
              "frame %.2f ms (medians)%s%s\n",
              o.scene.c_str(), settings.resolution.x, settings.resolution.y, low.x, low.y, desc.lights.size(),
              frames, median(volumetric) / 1000.0, median(total) / 1000.0, o.output.empty() ? "" : " -> ",
              o.output.c_str());
  std::string methods;
  for (size_t i = 0; i < desc.lights.size(); ++i)
    if (desc.options(i).volumetric)
      methods += (methods.empty() ? "" : ", ") + std::to_string(i) + " " + light_method(desc, settings, scatterer, i);
  std::printf("volumetric method (--method %s) per light: %s\n", o.method.c_str(),
              methods.empty() ? "no volumetric lights" : methods.c_str());
  if (!changes.empty())
    std::printf("volumetric frame-to-frame change: %.2f %% (median over %zu frame pairs)\n", median(changes) * 100.0,
                changes.size());
}

// The passes shade point, spot, box and directional lights, and stand-ins for area lights and
// the environment (each named in a note); any other is named, never dropped silently (the
// --compare-reference path tracer does include it). Likewise glass the Embree scene buffers
// draw opaque.
void warn_about_what_is_not_drawn(const SceneDesc& desc, const RealtimeSettings& settings) {
  for (size_t i = 0; i < desc.lights.size(); ++i) {
    const Light& light = desc.lights[i];
    if (!is_shaded(light))
      std::fprintf(stderr,
                   "caligo: warning: light %zu (%s) is not shaded by the real-time passes (they shade point, spot, box "
                   "and directional lights); it is left out of every frame\n",
                   i, light_type_name(light));
    else if (const std::string as = stand_in_name(light, settings); !as.empty())
      std::fprintf(stderr, "caligo: note: light %zu (%s) is shaded in real time as %s\n", i, light_type_name(light),
                   std::holds_alternative<EnvironmentLight>(light)
                       ? (as + " by median cut, each with its shadow map (realtime.environment_lights)").c_str()
                       : ("a " + as + " light at its centre with its far-field intensity and a hard shadow").c_str());
  }
  if (settings.scene_buffers == SceneBufferMethod::embree &&
      std::any_of(desc.materials.begin(), desc.materials.end(),
                  [](const Material& m) { return std::holds_alternative<DielectricBsdf>(m.bsdf); }))
    std::fprintf(stderr, "caligo: warning: --scene-buffers embree draws glass (dielectric) surfaces opaque; the "
                         "rasteriser (the default) shows what lies behind them\n");
}

}  // namespace

// The frame for the preview page: the composite, and its surfaces and volumetric light as layers.
Image preview_image(const RealtimeFrame& frame) {
  Image image = to_image(frame.color);
  const auto layer = [](const ColorPlanes& planes) {
    std::vector<RGB> out;
    for (int y = 0; y < planes.height(); ++y)
      for (int x = 0; x < planes.width(); ++x) out.push_back(planes.at(x, y));
    return out;
  };
  image = with_rgb_layer(image, "surfaces", layer(frame.surfaces));
  return with_rgb_layer(image, "volumetric", layer(frame.volumetric));
}

// The last frame's passes for the preview page, in microseconds.
std::string frame_table(const PassTimes& t) {
  char text[640];
  std::snprintf(text, sizeof text,
                "pass (last frame)        us\ndepth + normals   %8.0f\nshadow maps       %8.0f\naccumulation      %8.0f\n"
                "gather            %8.0f\nupsample          %8.0f\ntemporal          %8.0f\nsurfaces          %8.0f\n"
                "composite         %8.0f\ntotal             %8.0f\nvolumetric        %8.0f\n",
                t.depth, t.shadows, t.accumulation, t.gather, t.upsample, t.temporal, t.surfaces, t.composite, t.total,
                t.volumetric());
  return text;
}

int run_realtime(const RealtimeOptions& o) {
  const SceneDesc desc = load_scene(o.scene);
  const RealtimeSettings settings = settings_from(o, desc);
  const int frames = check_int(o.frames, 1, 100000, "--frames", desc.realtime.frames);
  check_realtime_options(o, desc);
  RealtimeOutputs outputs(o, desc, frames);  // every output is checked before any work

  print_scene_warnings(desc);
  warn_about_what_is_not_drawn(desc, settings);
  RealtimePipeline pipeline(Scene::build(desc), settings);
  const VolumetricMethod method = settings.froxel ? VolumetricMethod::kMarch : *parse_volumetric_method(o.method);
  HybridScatterer* scatterer = nullptr;  // owned by the pipeline
  if (method != VolumetricMethod::kMarch) {
    TexturedSpotSettings spot;
    spot.model = *spot_model_of(o.spot_model);
    auto owned = std::make_unique<HybridScatterer>(pipeline.scene(), method, HybridSettings{}, spot);
    scatterer = owned.get();
    pipeline.set_scatterer(std::move(owned));
  }
  std::atomic<bool> stop_requested{false};
  const std::unique_ptr<PreviewServer> preview =
      start_preview(o.preview, [&stop_requested] { stop_requested = true; }, o.view == "filmic");
  const auto start = std::chrono::steady_clock::now();
  std::vector<PassTimes> timed;
  float time = 0.0f;
  const RealtimeFrame* last_frame = nullptr;
  ColorPlanes previous_volumetric;
  std::vector<double> changes;
  for (int i = 0; i < frames; ++i) {
    time = o.still_time ? *o.still_time : float(i) / desc.realtime.fps;
    const RealtimeFrame& frame = pipeline.render(time, uint32_t(i));
    last_frame = &frame;
    if (i > 0) changes.push_back(frame_change(frame.volumetric, previous_volumetric));
    previous_volumetric = frame.volumetric;
    if (i >= std::min(o.warmup, frames - 1)) timed.push_back(frame.times);
    if (outputs.wants_frame(i == frames - 1)) outputs.frame(to_image(frame.color), i, i == frames - 1);
    if (preview) {
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      preview->publish({preview_image(frame), i + 1, frames, seconds, i == frames - 1, frame_table(frame.times)});
      if (stop_requested) {
        std::fprintf(stderr, "caligo: stopped from the preview page after %d of %d frames; nothing written\n", i + 1, frames);
        return kExitInterruptedBase + SIGINT;
      }
    }
  }
  if (preview) preview->linger(2.0);

  if (!o.quiet) print_table(desc, settings, timed, scatterer);
  print_summary(o, desc, settings, frames, timed, scatterer, changes);
  if (o.compare_reference) compare_with_reference(o, desc, settings, time, *last_frame, outputs);
  outputs.commit(settings.resolution.x, settings.resolution.y, desc.realtime.fps);
  return 0;
}

}  // namespace caligo
