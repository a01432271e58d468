// caligo render's command line: every option and flag, registered with CLI11 (the values are
// read and checked by render_command.cpp).
#include <CLI/CLI.hpp>

#include <string>

#include "commands.h"
#include "lights/light_sampler.h"
#include "render/render.h"

namespace caligo {

namespace {

// How a path is traced: limits and estimator choices (settings/path_settings.h).
void add_path_options(CLI::App* cmd, RenderOptions& o) {
  cmd->add_option("--max-bounces,--max-depth", o.max_bounces,
                  "Maximum bounces: each surface bounce and each run of consecutive scattering events in "
                  "media counts one; 1 is direct light only (overrides the scene; --max-depth is an alias)");
  cmd->add_option("--max-volume-bounces", o.max_volume_bounces,
                  "Maximum scattering events in media, runs included (overrides the scene)");
  cmd->add_option("--distance-sampling", o.distance_sampling,
                  "Distance sampling for light in media: mis (default; equiangular share by optical depth), mis-fixed (share 3/4), density or equiangular");
  cmd->add_option("--secondary", o.secondary,
                  "How segments after the camera segment and their shadow rays estimate volumes: auto (default: "
                  "spectral and ratio tracking through heterogeneous media, closed forms in homogeneous ones), "
                  "track (tracking everywhere) or march (decoupled ray marching, the former behaviour)")
      ->default_str("auto");
  cmd->add_option("--deferred-nee", o.deferred_nee,
                  "Connect K scattering vertices per path to lights after building it (0: each segment as it goes)");
  cmd->add_option("--guiding", o.guiding,
                  "Path guiding: learn where light comes from in training passes of doubling sample counts and "
                  "sample scattering directions from it at diffuse surfaces, in media, both or nowhere: "
                  "off, surface, volume or all (overrides the scene's render.guiding)")
      ->default_str("off");
  cmd->add_option("--light-sampler", o.light_sampler,
                  "How next-event estimation picks a light: tree (light tree: importance at the receiver, "
                  "lights at infinity weighed there too), power (in proportion to power, the same everywhere), "
                  "uniform, or tree-fixed-share (the former tree: lights at infinity by a fixed share of power)")
      ->default_str(light_sampler_name(PathSettings{}.light_sampler));
}

}  // namespace

void add_render_command(CLI::App& app, RenderOptions& o) {
  CLI::App* cmd = app.add_subcommand("render", "Render a scene file or a built-in scene to OpenEXR + PNG");
  cmd->add_option("scene", o.scene, "Scene file (.json) or built-in name (see --list-builtins)");
  cmd->add_option("-o,--output", o.output, "Output OpenEXR file; a PNG preview is written beside it")
      ->default_str("<scene name>.exr");
  cmd->add_option("--spp", o.spp, "Samples per pixel (overrides the scene)");
  cmd->add_option("--res", o.resolution, "Resolution WxH, e.g. 640x480 (overrides the scene)");
  cmd->add_option("--threads", o.threads, "Worker threads (default: all cores)");
  cmd->add_option("--seed", o.seed, "Random seed (overrides the scene)");
  add_path_options(cmd, o);
  cmd->add_option("--filter", o.filter,
                  "Pixel filter, importance-sampled: box (radius 0.5 px), gaussian (radius 1.5, sigma 0.5) or "
                  "blackman_harris (radius 0.75, Cycles' width 1.5) (overrides the scene's render.filter)");
  cmd->add_option("--crop", o.crop,
                  "x0,x1,y0,y1: render only this part of the image, as fractions of its width and height from "
                  "the top-left corner, e.g. 0.25,0.75,0,0.5 (overrides the scene's render.crop)");
  cmd->add_option("--aov", o.aovs,
                  "Outputs written besides the beauty (R, G, B), comma-separated: alpha, depth, normal, albedo, "
                  "surface_direct, surface_indirect, volume_direct, volume_indirect, surface_emission, "
                  "volume_emission, background, or lights (the seven light layers, which add up to the "
                  "beauty), default (alpha, depth, normal, albedo) or all (overrides the scene's render.aovs)")
      ->default_str("default");
  cmd->add_option("--time", o.time, "Render the scene at this time in seconds (camera path, light keys)");
  cmd->add_option("--frames", o.frames,
                  "Render frames A..B (or one frame N): {frame} or {frame:04} in -o and in the scene's file names "
                  "becomes the frame's number, its time is frame / --fps");
  cmd->add_option("--fps", o.fps, "Frames per second of --frames (default 24)");
  cmd->add_option("--exposure", o.exposure, "Exposure of the PNG preview, in stops");
  cmd->add_option("--view", o.view,
                  "Tone curve of the PNG preview: filmic (the ACES fit, default) or standard (sRGB, clipped at 1)")
      ->check(CLI::IsMember({"filmic", "standard"}));
  cmd->add_option("--priority", o.priorities,
                  "MATERIAL=LEVEL: set a medium-bounding material's priority (an integer, or off, very_high, "
                  "high, normal, low, very_low); repeatable")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  cmd->add_flag("--list-builtins", o.list_builtins, "List the built-in scenes and exit");
  cmd->add_flag("-q,--quiet", o.quiet, "No progress output");
  cmd->add_option("--preview", o.preview,
                  "Serve a live preview page on 127.0.0.1 (PORT, or any free port) while rendering; the URL, with its "
                  "access token, is printed")
      ->expected(0, 1);
  cmd->add_flag("--single-pass", o.single_pass,
                "Render each tile's samples at once, tile after tile (the former order), instead of refining the whole "
                "frame in passes of doubling sample counts; an interrupted render then has unrendered tiles");
  cmd->add_flag("--denoise", o.denoise,
                "Render two half-sample films and write the denoised beauty as the layer \"denoised\" (the PNG shows it)");
  cmd->add_option("--checkpoint", o.checkpoint,
                  "Save the film's raw sums to FILE as the render goes (every --checkpoint-every) and at the end, "
                  "so --resume can continue it; an interrupt (Ctrl-C, SIGTERM) saves one too");
  cmd->add_option("--checkpoint-every", o.checkpoint_every,
                  "How often to save the checkpoint: seconds, or 90s, 5m, 2h (default 60s)");
  cmd->add_option("--resume", o.resume,
                  "Continue the render saved in this checkpoint (same scene and settings; --spp may be raised); "
                  "the result equals an uninterrupted render bit for bit");
  cmd->add_option("--time-limit", o.time_limit,
                  "Progressive: a deadline (90, 90s, 5m): stop when the next pass would not fit, every pixel at "
                  "the same sample count (at most --spp); a pass that runs past it (a busy machine) is cut there, "
                  "pixels keeping their own counts");
  cmd->add_option("--target-rmse", o.target_rmse,
                  "Progressive: stop once the image's estimated RMSE (from each pixel's sample variance; adds the "
                  "variance layer) is at most this, in linear radiance (at most --spp samples)");
  cmd->add_option("--adaptive-threshold", o.adaptive_threshold,
                  "Adaptive sampling: a pixel stops once the estimated relative error of its mean (from its own "
                  "samples' variance; adds the variance layer) is below this, e.g. 0.01; pixel by pixel, unlike "
                  "--target-rmse, which stops the whole image (overrides the scene's render.adaptive)");
  cmd->add_option("--adaptive-min-samples", o.adaptive_min_samples,
                  "Adaptive sampling: samples every pixel takes before it may stop (default max(16, sqrt(spp)))");
  cmd->add_option("--clamp-direct", o.clamp_direct,
                  "Biased, off by default: limit each channel of a sample's direct light (and emission and "
                  "background seen) to this value; 0 is no limit");
  cmd->add_option("--clamp-indirect", o.clamp_indirect,
                  "Biased, off by default: limit each channel of a sample's indirect light to this value (fireflies "
                  "of caustics and rare paths go, energy with them); 0 is no limit");
  cmd->add_option("--mpi-split", o.mpi_split,
                  "Under mpirun or srun, how the ranks split the frame: samples (each rank a range of every "
                  "pixel's samples) or rows (each rank a band of rows, all samples); rank 0 merges and writes")
      ->check(CLI::IsMember({"samples", "rows"}))
      ->capture_default_str();
}

}  // namespace caligo
