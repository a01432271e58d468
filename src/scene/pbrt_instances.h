// pbrt-v4's object instancing (ObjectBegin / ObjectEnd / ObjectInstance), expanded: each
// instance becomes copies of its object's shapes with the instance's transform applied after
// their own, as pbrt composes them (render-from-instance after the shapes' definition CTMs).
// Caligo has no instanced geometry, so every copy costs its memory; a scene that would expand
// past kMaxInstancedShapes is refused at the ObjectInstance that would cross it.
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "scene/pbrt_builder.h"

namespace caligo::pbrt {

class ObjectInstancing {
 public:
  static constexpr size_t kMaxInstancedShapes = 1'000'000;

  bool defining() const { return open_.has_value(); }
  // ObjectBegin "name": the shapes `b` gets from now on belong to the object.
  void begin(const std::string& name, const std::string& where, const Builder& b);
  // ObjectEnd: moves the object's shapes (and their origins) out of `b.scene`.
  void end(const std::string& where, Builder& b);
  // ObjectInstance "name" under `ctm`.
  void instance(const std::string& name, const Mat4& ctm, const std::string& where, Builder& b);

 private:
  struct Definition {
    std::vector<Json> shapes;
    std::vector<std::string> wheres;  // each shape's directive
  };
  struct Open {
    std::string name, where;
    size_t first_shape = 0, first_origin = 0;
  };
  std::optional<Open> open_;
  std::map<std::string, Definition> objects_;
  size_t instanced_ = 0;
};

}  // namespace caligo::pbrt
