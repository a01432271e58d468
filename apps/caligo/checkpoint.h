// Checkpoints of `caligo render`: the film's raw sums and counts (Film::save), keyed by a hash
// of everything that decides the image except the sample count -- the scene's text, the
// settings, the time and the priority overrides -- so a checkpoint resumes only the render it
// came from (and may continue it to more samples).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "settings/render_settings.h"

namespace caligo {

// FNV-1a over the scene source (a file's bytes, or a built-in's JSON), caligo's version and a
// canonical text of the settings. Meshes, grids and images the scene refers to are not read:
// changing them between a checkpoint and its resume is not detected (nor is a rebuild of the
// same version with a changed integrator).
uint64_t checkpoint_key(const std::string& scene_source, const RenderSettings& settings, float time,
                        const std::vector<std::string>& priorities);

// The scene's source text for the key: the built-in's JSON or the file's bytes.
std::string scene_source(const std::string& scene_argument);

// "90", "90s", "5m", "2h" -> seconds; nullopt for anything else (or a non-positive value).
std::optional<double> parse_duration(const std::string& text);

}  // namespace caligo
