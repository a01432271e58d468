// What a scene file asks for that renders other than its author likely expects, found before the
// render, for the command line to print as warnings (the render still runs: the image is what the
// settings define, only probably not what was meant).
#pragma once

#include <string>
#include <vector>

#include "scene/scene_desc.h"

namespace caligo {

// With render.priority_shadows off (the default), a dielectric of priority other than off stops
// shadow rays, so whatever it encloses (the medium it bounds, objects inside) is lit only by
// light that refracts in: from a point, spot, box or sun light (a delta light) none can, as no
// path can hit such a light, and the inside renders black. One warning per such material that a
// shape uses, naming it and the setting, when the scene has a delta light.
std::vector<std::string> priority_shadow_warnings(const SceneDesc& scene);

}  // namespace caligo
