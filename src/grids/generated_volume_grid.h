// The generator's grids as a VolumeGrid, for scenes that name a procedural volume instead of
// a file ({"type": "vdb", "generate": {...}}), so the built-in scenes need no file on disk.
#pragma once

#include <memory>

#include "grids/grid_generate.h"
#include "grids/volume_grid.h"

namespace caligo {

// Generated once per process for each (kind, resolution, seed) and shared afterwards: a scene
// loaded twice, or at several times of an animation, does not pay for generation again.
std::shared_ptr<const VolumeGrid> generated_volume_grid(const GenerateSettings& settings);

}  // namespace caligo
