// Reading media and volume primitives from scene JSON (see docs/scene-format.md).
#pragma once

#include <string>
#include <vector>

#include "scene/json_reader.h"
#include "volumes/volume.h"

namespace caligo {

struct NamedMedium {
  std::string name;
  VolumeShader shader;
};

// "media": {"fog": {...}, ...}
std::vector<NamedMedium> parse_media(const JsonCursor& c);
// One element of "volumes": a convex shape filled with a named medium.
VolumePrimitive parse_volume(const JsonCursor& c, const std::vector<NamedMedium>& media);

}  // namespace caligo
