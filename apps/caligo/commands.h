// The subcommands of the caligo command line; each lives in its own file.
#pragma once

#include <optional>
#include <utility>
#include <string>
#include <vector>

#include "core/error.h"
#include "scene/scene_desc.h"

namespace CLI {
class App;
}

namespace caligo {

struct RenderOptions {
  std::string scene;   // a scene file or a built-in's name
  std::optional<std::string> output;  // .exr path (default: the scene's name); a .png preview beside it
  std::optional<int> spp;
  std::optional<std::string> resolution;  // "WxH"
  std::optional<int> threads;
  std::optional<std::string> seed;  // parse_seed: text, so that -1 and 2^64 are refused, not wrapped
  // PathSettings (settings/path_settings.h), each overriding the scene's or the default.
  std::optional<int> max_bounces;  // --max-bounces, alias --max-depth
  std::optional<int> max_volume_bounces;
  std::optional<std::string> distance_sampling;
  std::optional<std::string> secondary;
  std::optional<int> deferred_nee;
  std::optional<std::string> guiding;
  std::optional<float> adaptive_threshold;  // --adaptive-threshold X
  std::optional<int> adaptive_min_samples;
  std::optional<float> clamp_direct, clamp_indirect;
  std::optional<std::string> light_sampler;
  std::optional<std::string> filter;  // --filter box|gaussian|blackman_harris (its default radius)
  std::optional<std::string> crop;    // --crop x0,x1,y0,y1: fractions of the image
  std::optional<std::string> aovs;    // --aov LIST: the outputs besides the beauty (settings/aov.h)
  float time = 0.0f;  // seconds: the camera on its path and the lights on their keys at this time
  std::optional<std::string> frames;  // --frames A..B (render_frames.cpp)
  float fps = 24.0f;                  // --fps: a frame's time is frame / fps
  std::optional<int> frame;           // the frame being rendered: "{frame}" in the scene's file names
  float exposure = 0.0f;
  std::string view = "filmic";  // --view filmic|standard: the PNG preview's tone curve
  bool single_pass = false;      // --single-pass: the former tile-by-tile order (no refinement passes)
  std::optional<std::string> preview;  // --preview [PORT]: the live page (preview_server.h); "" any port
  bool denoise = false;          // --denoise: two half-sample films and the denoised layer (render_denoised.cpp)
  std::vector<std::string> priorities;  // --priority MATERIAL=LEVEL, applied in order
  bool list_builtins = false;
  bool quiet = false;
  std::string mpi_split = "samples";  // --mpi-split samples|rows: under mpirun (distributed/share.h)
  // Checkpoints and progressive rendering (render/progressive.h, driven by render_command.cpp).
  std::optional<std::string> checkpoint;        // --checkpoint FILE
  std::optional<std::string> checkpoint_every;  // --checkpoint-every 60s
  std::optional<std::string> resume;            // --resume FILE
  std::optional<std::string> time_limit;        // --time-limit 90s
  std::optional<double> target_rmse;            // --target-rmse X
};

struct CompareOptions {
  std::string a, b;
  std::optional<double> max_rmse;
};

struct RealtimeOptions {
  std::string scene;
  std::string output;  // a folder for frames, a .gif, or a .png/.exr for the last frame only
  std::optional<int> frames;
  std::optional<std::string> resolution;
  std::optional<std::string> scale;          // full, half, quarter
  std::string method = "march";              // march (Lords of the Fallen), none, brute or hybrid
  std::string spot_model = "auto";           // textured spots: auto, airlight or hoffman-preetham
  std::optional<std::string> froxels;        // --method froxel: the grid, WxHxD
  std::string scene_buffers = "raster";      // raster or embree
  std::optional<int> samples;
  std::optional<int> tile_size;
  std::optional<int> gather_radius;
  std::optional<int> scatter_gather_radius;
  std::optional<float> ms_floor;
  std::optional<std::string> steps;  // uniform or equiangular
  std::optional<bool> temporal;
  std::optional<bool> light_cores;
  std::optional<float> still_time;  // --time: every frame at this time (a still scene)
  int warmup = 3;
  bool exr = false;
  bool scalar = false;
  bool compare_reference = false;
  int reference_spp = 256;
  bool reference_per_light = false;
  float exposure = 0.0f;
  std::string view = "filmic";  // --view filmic|standard
  std::optional<std::string> preview;  // --preview [PORT]
  bool quiet = false;
};

struct GenerateOptions {
  std::string kind;    // cloud, smoke, fire
  std::string output;  // .vdb or .nvdb
  int resolution = 128;
  std::string seed = "1";  // parse_seed
  bool quiet = false;
};

struct BenchTableOptions {
  std::string table;  // wyman
  int resolution = 1024;
  std::string scales = "1,4";
  int frames = 5;
  int reference_spp = 64;
  std::string scenes;  // comma separated; empty: the table's own scenes
  std::string output;  // a folder: table.md and one PNG per scene
  float exposure = 0.0f;
};

struct DenoiseOptions {
  std::string input, output;
  std::optional<std::string> reference;  // --reference: true errors and a comparison strip
  int radius = 4;
  float exposure = 0.0f;
  std::string view = "filmic";
  bool quiet = false;
};

struct InfoOptions {
  std::string file;  // .vdb or .nvdb
};

struct SceneCommandOptions {
  enum Action { kList, kShow } action = kList;
  std::string name;  // show: a built-in's name
};

inline const SourceLocation kCommandLine{"command line", ""};

// A scene file or a built-in's name; InputError when it is neither.
SceneDesc load_scene(const std::string& name, std::optional<int> frame = std::nullopt);
// --frames A..B (or N): the first and last frame.
std::pair<int, int> parse_frame_range(const std::string& text);
int run_render_sequence(const RenderOptions& options);
// The scene's reading warnings (SceneDesc::warnings) on stderr, one "caligo: warning:" line each.
void print_scene_warnings(const SceneDesc& desc);
// "WxH" of --res; InputError otherwise.
Vec2i parse_resolution(const std::string& text);
// A --seed: a decimal integer in [0, 2^63); a located InputError naming the option otherwise.
uint64_t parse_seed(const std::string& text);

void add_render_command(CLI::App& app, RenderOptions& options);
void add_realtime_command(CLI::App& app, RealtimeOptions& options);
int run_realtime(const RealtimeOptions& options);
void add_compare_command(CLI::App& app, CompareOptions& options);
int run_render(const RenderOptions& options);
int run_compare(const CompareOptions& options);
void add_generate_command(CLI::App& app, GenerateOptions& options);
int run_generate(const GenerateOptions& options);
void add_info_command(CLI::App& app, InfoOptions& options);
void add_scene_command(CLI::App& app, SceneCommandOptions& options);
int run_scene(const SceneCommandOptions& options);
int run_info(const InfoOptions& options);
void add_denoise_command(CLI::App& app, DenoiseOptions& options);
int run_denoise(const DenoiseOptions& options);
void add_bench_table_command(CLI::App& app, BenchTableOptions& options);
int run_bench_table(const BenchTableOptions& options);

}  // namespace caligo
