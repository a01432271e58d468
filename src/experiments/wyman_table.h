// Wyman & Ramsey's Table 1 (2008) on our built-in scenes: frames per second of the volumetric
// methods (none, brute 150, hybrid 50, textured spotlight up to 150, and the march for
// reference) with scattering at each accumulation scale, each frame's relative RMSE against the
// path tracer's single-scattering reference, and the hybrid's speed-up over brute force at
// equal error. The textured column runs on the scene's spot-light twin (built-in NAME-spot,
// same occluders, a spot with a stained-glass gobo at the point light's place) against that
// scene's own reference; scenes without a twin show "–" there. `caligo bench-table wyman`
// (apps/caligo/bench_table_command.cpp) is its command line.
//
// What is measured. The scene's surfaces are made black (BlackBsdf) for the whole benchmark, so
// that both the real-time frame and the reference hold in-scattered light only: the error is
// the volumetric method's, not the simple surface shading's. Temporal reprojection is off
// (each frame stands alone, as in the paper, and one pipeline per scale can switch methods
// without a history from another method); the gather and upsampling stay on. Times are the
// median of the whole frame (PassTimes::total) over the timed frames after kWarmup frames.
//
// The reference is rendered once per scene as two halves of S/2 spp with different seeds and
// averaged. Their relative RMSE against each other is sqrt(2) x one half's noise, and the
// average's noise is one half's / sqrt(2): the reference's own noise is about rRMSE(A, B) / 2.
// It adds in quadrature to every method's error alike; the table reports it and the raw errors.
//
// Equal error: against the path tracer, every method carries the same errors of the real-time
// pipeline (shadow-map resolution, low-resolution scattering, upsampling) and the reference's
// noise, which at affordable spp hide the step error that separates brute force from the
// hybrid. Both methods integrate lit stretches in closed form and differ only in where they read
// visibility, so their error is measured against brute force with kConvergedSteps steps in the
// same pipeline (the "step error"). Brute force runs again with 25 to 600 steps (kBruteSweep);
// the match is the FEWEST steps whose step error is at most (1 + kMatchTolerance) x the
// hybrid's, and the speed-up is that brute run's frame time over the hybrid's. When no count
// matches, the speed-up against the most steps is a lower bound and is shown as ">=".
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "hybrid/hybrid_pipeline.h"
#include "realtime/reference_compare.h"
#include "scene/scene_desc.h"

namespace caligo {

namespace wyman {
inline constexpr int kWarmup = 2;
inline constexpr double kMatchTolerance = 0.10;  // relative: brute matches at step error <= 1.1 x hybrid's
inline constexpr int kBruteSweep[] = {25, 50, 100, 150, 300, 600};  // ascending; 150 is the table's
inline constexpr int kConvergedSteps = 2000;
}  // namespace wyman

struct WymanTableSettings {
  int resolution = 1024;             // square output, N x N
  std::vector<int> scales = {1, 4};  // accumulation scales (1: full resolution, 4: 1/4)
  int frames = 5;                    // timed frames per method after the warm-up
  int reference_spp = 64;            // of the path-traced reference
  std::vector<std::string> scenes = {"wyman-20k", "wyman-70k", "wyman-330k", "wyman-750k"};
  float exposure = 0.0f;  // of the preview strips, in stops
};

// One column of the experiment: a volumetric method and how it runs.
struct WymanVariant {
  std::string label;
  VolumetricMethod method;
  int brute_samples = 150;
  bool in_main_table = true;
  bool converged = false;  // the step-error yardstick of its scene: one untimed frame
  bool spot = false;       // runs on the scene's textured-spotlight twin (NAME-spot)
  int spot_steps = 0;      // textured: min = max steps (0: the pass's own 16..150 rule)
};

// The main table's variants, then the brute sweep's other counts, then the two converged
// yardsticks (textured and brute kConvergedSteps).
std::vector<WymanVariant> wyman_variants();

struct WymanRun {
  bool ran = false;  // false: a spot variant on a scene without a textured-spotlight twin
  double frame_us = 0, volumetric_us = 0;
  double reference_noise = 0;  // of the reference the error is measured against
  ReferenceError error;        // against the path tracer
  double step_error = 0;       // relative RMSE against brute kConvergedSteps of the same pipeline
  std::string used;            // the method the light actually took (hybrid may fall back to brute)
};

struct WymanSceneResult {
  std::string name;
  uint64_t triangles = 0;  // of the generated occluders; 0: unknown (mesh files)
  double reference_noise = 0;
  int reference_spp = 0;
  std::vector<std::vector<WymanRun>> runs;  // [scale][variant]
};

struct WymanTableResults {
  WymanTableSettings settings;
  std::vector<WymanVariant> variants;
  std::vector<WymanSceneResult> scenes;
};

// A scene of the table with its surfaces made black, and its textured-spotlight twin.
struct WymanScene {
  std::string name;
  SceneDesc desc;
  std::optional<SceneDesc> spot;  // the built-in NAME-spot, when there is one
};

// A scene file or built-in by name (the command line's loader); throws InputError.
using SceneLoader = std::function<SceneDesc(const std::string& name)>;

// Loads settings.scenes and their twins, all before any work: throws the loader's InputError,
// or InputError for emissive materials (light the volumetric methods do not model).
std::vector<WymanScene> load_wyman_scenes(const WymanTableSettings& settings, const SceneLoader& load);

struct WymanTableHooks {
  // A progress line (no newline), such as "wyman-20k: reference 64x64 at 4 spp...".
  std::function<void(const std::string& line)> progress;
  // When set, each scene's previews side by side once the scene is done: one row per scale,
  // the main table's methods, the reference and the spot reference (PNG-ready 8-bit sRGB).
  std::function<void(const std::string& scene, const Rgb8Image& strip)> preview;
};

// Runs the experiment on `scenes` (from load_wyman_scenes) with `settings`' resolution,
// scales, frames, reference spp and exposure.
WymanTableResults run_wyman_table(const WymanTableSettings& settings, const std::vector<WymanScene>& scenes,
                                  const WymanTableHooks& hooks = {});

// The report: Table 1 (frames per second), the errors against the reference, the step errors
// and the equal-error speed-up, as markdown (wyman_report.cpp).
std::string wyman_markdown(const WymanTableResults& results);

}  // namespace caligo
