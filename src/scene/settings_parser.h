// Reading the camera, "render" and "realtime" objects of scene JSON (docs/scene-format.md):
// each checked key by key, with located errors, into the scene description's settings.
#pragma once

#include "scene/json_reader.h"
#include "scene/scene_desc.h"

namespace caligo {

CameraDesc parse_camera(const JsonCursor& c);
RenderSettings parse_render(const JsonCursor& c);
RealtimeSettings parse_realtime(const JsonCursor& c);

}  // namespace caligo
