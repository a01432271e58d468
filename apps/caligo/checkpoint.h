// Checkpoints of `caligo render`: the film's raw sums and counts (Film::save, which guards them
// with a CRC-32), keyed by a hash of everything that decides the image except the sample count
// -- the scene's text, the content of every file it reads, the settings, the time and the
// priority overrides -- so a checkpoint resumes only the render it came from (and may continue
// it to more samples), and MPI ranks whose scene or assets differ refuse to share a frame.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "settings/render_settings.h"

namespace caligo {

// FNV-1a over the scene source (a file's bytes, or a built-in's JSON), the size and CRC-32 of
// each file the scene reads (SceneDesc::files, in order; by content, not by name or time, so a
// copy on another machine keys the same), caligo's version and a canonical text of the
// settings. A rebuild of the same version with a changed integrator is not detected.
uint64_t checkpoint_key(const std::string& scene_source, const std::vector<std::string>& files,
                        const RenderSettings& settings, float time, const std::vector<std::string>& priorities);

// The scene's source text for the key: the built-in's JSON or the file's bytes.
std::string scene_source(const std::string& scene_argument);

// "90", "90s", "5m", "2h" -> seconds; nullopt for anything else (or a non-positive value).
std::optional<double> parse_duration(const std::string& text);

}  // namespace caligo
