#include "scene/pbrt_instances.h"

#include "core/message_text.h"

namespace caligo::pbrt {

void ObjectInstancing::begin(const std::string& name, const std::string& where, const Builder& b) {
  if (open_) fail_at(where, "ObjectBegin inside the definition of object " + quote_for_message(open_->name) + " (" +
                                open_->where + ")");
  if (objects_.count(name)) fail_at(where, "ObjectBegin: object " + quote_for_message(name) + " is already defined");
  const size_t shapes = b.scene.contains("shapes") ? b.scene["shapes"].size() : 0;
  open_ = Open{name, where, shapes, b.origins.size()};
}

void ObjectInstancing::end(const std::string& where, Builder& b) {
  if (!open_) fail_at(where, "ObjectEnd without ObjectBegin");
  Definition d;
  Json& shapes = b.scene["shapes"];
  for (size_t i = open_->first_shape; i < shapes.size(); ++i) d.shapes.push_back(std::move(shapes[i]));
  shapes.erase(shapes.begin() + std::ptrdiff_t(open_->first_shape), shapes.end());
  // The shapes' origins leave with them; those of materials defined meanwhile stay.
  std::vector<std::pair<std::string, std::string>> kept(b.origins.begin(), b.origins.begin() + std::ptrdiff_t(open_->first_origin));
  for (size_t i = open_->first_origin; i < b.origins.size(); ++i) {
    if (b.origins[i].first.rfind("/shapes/", 0) == 0) d.wheres.push_back(b.origins[i].second);
    else kept.push_back(b.origins[i]);
  }
  b.origins = std::move(kept);
  objects_[open_->name] = std::move(d);
  open_.reset();
}

void ObjectInstancing::instance(const std::string& name, const Mat4& ctm, const std::string& where, Builder& b) {
  if (open_) fail_at(where, "ObjectInstance inside the definition of object " + quote_for_message(open_->name));
  const auto it = objects_.find(name);
  if (it == objects_.end()) fail_at(where, "ObjectInstance: no object " + quote_for_message(name));
  const Definition& d = it->second;
  instanced_ += d.shapes.size();
  if (instanced_ > kMaxInstancedShapes)
    fail_at(where, "ObjectInstance: instancing expands to more than " + std::to_string(kMaxInstancedShapes) +
                       " shapes, which Caligo (without instanced geometry) does not hold");
  if (determinant3(ctm) < 0.0f)
    b.warnings.push_back(where + ": ObjectInstance: a mirroring instance transform; the instance's winding is kept");
  Json matrix = Json::array();
  for (const auto& row : ctm.m)
    for (float v : row) matrix.push_back(v);
  Json& shapes = b.scene["shapes"];
  for (size_t i = 0; i < d.shapes.size(); ++i) {
    Json shape = d.shapes[i];
    if (!(ctm == Mat4::identity())) {
      if (!shape.contains("transform")) shape["transform"] = Json::array();
      shape["transform"].push_back(Json{{"matrix", matrix}});  // applied after the shape's own
    }
    b.add_origin("/shapes/" + std::to_string(shapes.size()), d.wheres[i]);
    shapes.push_back(std::move(shape));
  }
}

}  // namespace caligo::pbrt
