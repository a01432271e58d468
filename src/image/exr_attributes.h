// Header attributes of an OpenEXR file beside its channels: what a render records about itself
// (software, samples, time, seed, scene) and the camera matrices compositors read. The names of
// OpenEXR's standard attributes are kept where one exists (worldToCamera, worldToNDC, capDate,
// utcOffset); Caligo's own go under "caligo/".
#pragma once

#include <string>
#include <variant>
#include <vector>

#include "core/transform.h"

namespace caligo {

// A Mat4 is Caligo's column-vector matrix (p' = M p); it is written as OpenEXR's M44f, whose
// convention is Imath's row vectors (p' = p M), that is transposed, and read back the same way.
using ExrValue = std::variant<std::string, int, float, Mat4>;

struct ExrAttribute {
  std::string name;
  ExrValue value;
  bool operator==(const ExrAttribute&) const = default;
};

using ExrAttributes = std::vector<ExrAttribute>;

// The value of `name`, or nullptr.
const ExrValue* find_attribute(const ExrAttributes& attributes, const std::string& name);

}  // namespace caligo
