// Reading media and volume primitives from scene JSON (see docs/scene-format.md).
#pragma once

#include <string>
#include <vector>

#include "scene/json_reader.h"
#include "scene/scene_desc.h"
#include "scene/shared_readers.h"
#include "volumes/volume.h"

namespace caligo {

// "media": {"fog": {...}, ...}
std::vector<NamedMedium> parse_media(const JsonCursor& c);
// The index in `media` of the medium named by the string `c` holds; a located error listing
// the defined media otherwise.
int find_medium(const JsonCursor& c, const std::vector<NamedMedium>& media);
// One element of "volumes": a sphere, box or closed mesh filled with a named medium, or a
// grid (VDB/NanoVDB file, raw dense array or the generator) giving that medium's density.
// Files are read now, resolved (and recorded) by `files`. Sets VolumePrimitive::medium to the
// medium's index.
VolumePrimitive parse_volume(const JsonCursor& c, const std::vector<NamedMedium>& media, SceneFiles& files);

}  // namespace caligo
