// Keyframe interpolation for camera paths and light animation (SceneDesc::at_time).
//
// Linear interpolation, or Catmull-Rom as a cubic Hermite spline whose tangents are the
// central differences in time, (p[i+1] - p[i-1]) / (t[i+1] - t[i-1]), one-sided at the ends:
// it passes through every key, has a continuous velocity even with unevenly spaced keys,
// and reproduces uniform motion exactly. Outside the key range the first or last value holds.
#pragma once

#include <vector>

#include "core/vec.h"
#include "scene/scene_desc.h"

namespace caligo {

// `times` strictly increasing, same length as `values`, at least one key.
Vec3 interpolate_keys(const std::vector<float>& times, const std::vector<Vec3>& values, Interpolation mode,
                      float time);

}  // namespace caligo
