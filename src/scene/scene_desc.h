// The parsed, validated contents of a scene file, before anything is built. Every field
// holds a value that passed validation; SourceLocations are kept where the scene builder
// can still fail (mesh files) so its errors point into the scene file too.
#pragma once

#include <string>
#include <variant>
#include <vector>

#include "core/error.h"
#include "core/transform.h"
#include "core/vec.h"
#include "lights/light.h"
#include "materials/material.h"
#include "volumes/volume.h"

namespace caligo {

struct CameraDesc {
  Vec3 position{0, 0, 5};
  Vec3 look_at{0, 0, 0};
  Vec3 up{0, 1, 0};
  float fov_degrees = 40.0f;  // vertical field of view
  Vec2i resolution{640, 480};
};

struct RenderDefaults {
  int spp = 16;
  int max_depth = 8;             // surface bounces
  int max_volume_bounces = 128;  // scattering events inside media
  uint64_t seed = 0;
};

struct SphereShape {
  Vec3 center;
  float radius = 1.0f;
};
struct BoxShape {
  Vec3 min, max;
};
struct RectangleShape {
  Vec3 corner, edge1, edge2;  // normal = normalize(cross(edge1, edge2))
};
// A triangle mesh from a file: OBJ (tinyobjloader) or glTF 2.0 (.gltf/.glb, tinygltf).
struct MeshFileShape {
  std::string path;              // absolute, or relative to the working directory
  bool skip_degenerate = false;  // remove zero-area triangles instead of rejecting the file
};
using ShapeGeometry = std::variant<SphereShape, BoxShape, RectangleShape, MeshFileShape>;

struct ShapeDesc {
  ShapeGeometry geometry;
  Transform transform;   // object to world
  int material = 0;      // index into SceneDesc::materials
  SourceLocation where;  // e.g. {"room.json", "/shapes/3"}
};

struct SceneDesc {
  std::string file;  // the scene file's name as given (or "builtin:NAME")
  CameraDesc camera;
  RenderDefaults render;
  std::vector<Material> materials;
  std::vector<ShapeDesc> shapes;
  std::vector<Light> lights;  // sphere and quad lights also become visible geometry
  std::vector<VolumePrimitive> volumes;
};

}  // namespace caligo
