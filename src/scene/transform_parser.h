// Reading transforms, directions and box corners from scene JSON (shared by shapes, lights
// and volumes).
#pragma once

#include "core/transform.h"
#include "scene/json_reader.h"

namespace caligo {

// A non-zero vec3, normalised.
Vec3 read_direction(const JsonCursor& c);
// An array of operations ({"translate"}, {"rotate"}, {"scale"}, {"matrix"}) applied in the
// order written: [op1, op2, ...] is ... * op2 * op1. Fails on a singular result.
Transform parse_transform(const JsonCursor& c);

// Lengths in metres that float geometry can represent reliably: from a micrometre to
// 10,000 km. Sizes outside this range make intersection tests lose all precision.
inline constexpr double kMinSize = 1e-6;
inline constexpr double kMaxSize = 1e7;
inline Range size_range() { return Range::closed(kMinSize, kMaxSize); }

struct BoxCorners {
  Vec3 min, max;
};
// The "min" and "max" keys of a box, with max - min in [kMinSize, kMaxSize] in every component.
BoxCorners read_box_corners(ObjectReader& r);

}  // namespace caligo
