// Reading transforms and directions from scene JSON (shared by shapes, lights and volumes).
#pragma once

#include "core/transform.h"
#include "scene/json_reader.h"

namespace caligo {

// A non-zero vec3, normalised.
Vec3 read_direction(const JsonCursor& c);
// An array of operations ({"translate"}, {"rotate"}, {"scale"}, {"matrix"}) applied in the
// order written: [op1, op2, ...] is ... * op2 * op1. Fails on a singular result.
Transform parse_transform(const JsonCursor& c);

}  // namespace caligo
