// What `caligo render` records in its EXR header, as renderers do: the software and version,
// the samples each pixel actually holds, the render time, the seed, the scene, when it was made,
// and the camera as OpenEXR's worldToCamera and worldToNDC (Nuke reads them to rebuild the camera).
#pragma once

#include <cstdint>
#include <string>
#include <utility>

#include "image/exr_attributes.h"
#include "scene/camera.h"

namespace caligo {

struct RenderRecord {
  std::string scene;             // the file, or "builtin:NAME"
  uint64_t seed = 0;
  std::pair<int, int> samples;   // the fewest and most samples a pixel holds
  double seconds = 0.0;          // wall time of the render (this run; a resumed one adds)
};

// "Caligo VERSION".
std::string software_name();

ExrAttributes render_attributes(const RenderRecord& record, const Camera& camera);

}  // namespace caligo
