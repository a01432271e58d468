// Procedural grids, so that VDB rendering can be exercised without downloading any file:
// a cumulus cloud, a smoke plume and a fireball. Deterministic for a seed (any thread count).
//
// World placement (metres, y up), voxel size = longest box edge / resolution:
//   cloud  [-2, 2] x [0, 2.5] x [-2, 2]    "density" in [0, 1]: a union of displaced
//          spheres with billowy (cauliflower) fractal displacement, a flat-ish base and an
//          eroded, sharp-but-noisy edge (about 0.1 m). At resolution 128: 0.03125 m voxels.
//   smoke  [-1.25, 1.25] x [0, 4] x [-1.25, 1.25]   "density" in [0, 1]: a rising plume that
//          widens with height, domain-warped by turbulent noise, its axis swaying, fading out
//          towards the top. At resolution 128: 0.03125 m voxels.
//   fire   [-1.5, 1.5] x [0, 3] x [-1.5, 1.5]   a fireball around (0, 1.35, 0), radius ~0.75 m:
//          "density" in [0, 1] (soot: a noisy shell around the ball, a little inside),
//          "temperature" in KELVIN directly (0 outside, ~900 K at the ball's edge, up to
//          3000 K in the core: use temperature scale 1, offset 0), and "flame" in [0, 1]
//          (the burning zone, a noisy shell inside the ball, for flame/emission shading).
//          At resolution 128: 0.0234 m voxels.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/bounds.h"
#include "grids/sparse_float_grid.h"

namespace caligo {

enum class GeneratedVolume { kCloud, kSmoke, kFire };

inline constexpr int kMinGenerateResolution = 8;
inline constexpr int kMaxGenerateResolution = 1024;

struct GenerateSettings {
  GeneratedVolume kind = GeneratedVolume::kCloud;
  int resolution = 128;  // voxels along the box's longest edge
  uint64_t seed = 1;
};

std::optional<GeneratedVolume> parse_generated_volume(const std::string& name);  // "cloud", "smoke", "fire"
Bounds3 generated_bounds(GeneratedVolume kind);

// The grids (density first). A resolution outside [8, 1024] is an InputError.
std::vector<SparseFloatGrid> generate_grids(const GenerateSettings& settings);

}  // namespace caligo
