// The `many-lamps` built-in scene, generated in code (1,000 lights): see builtin_many_lamps.cpp.
#pragma once

#include <string>

namespace caligo {

std::string many_lamps_scene();

}  // namespace caligo
