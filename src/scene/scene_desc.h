// The parsed, validated contents of a scene file, before anything is built. Every field
// holds a value that passed validation; SourceLocations are kept where the scene builder
// can still fail (mesh files) so its errors point into the scene file too.
#pragma once

#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "core/crop_window.h"
#include "core/enum_names.h"
#include "core/error.h"
#include "core/transform.h"
#include "core/vec.h"
#include "settings/realtime_settings.h"
#include "settings/render_settings.h"
#include "lights/light.h"
#include "materials/material.h"
#include "volumes/volume.h"

namespace caligo {

enum class Interpolation { linear, catmull_rom };

// A camera keyframe: where the camera is and what it looks at, at a time in seconds.
struct CameraKey {
  float time = 0.0f;
  Vec3 position, look_at;
};

enum class CameraProjection { perspective, orthographic };

struct CameraDesc {
  Vec3 position{0, 0, 5};
  Vec3 look_at{0, 0, 0};
  Vec3 up{0, 1, 0};
  float fov_degrees = 40.0f;  // vertical field of view
  Vec2i resolution{640, 480};
  // Keyframes in increasing time (empty: a still camera at position/look_at). Before the
  // first key and after the last the camera holds still.
  std::vector<CameraKey> path;
  Interpolation path_interpolation = Interpolation::linear;
  // Projection and lens (scene/camera.h). Orthographic: a window `ortho_width` metres wide
  // (height from the aspect ratio) through `position`, rays parallel to the view axis;
  // fov and the lens are unused. Perspective: a pinhole unless the lens has an aperture,
  // given as a radius in metres or as an f-number (at most one of the two is non-zero).
  CameraProjection projection = CameraProjection::perspective;
  float ortho_width = 0.0f;      // metres; > 0 when orthographic
  float aperture_radius = 0.0f;  // metres; 0: pinhole
  float fstop = 0.0f;            // f-number N (aperture diameter = focal length / N); 0: not given
  float focus_distance = 0.0f;   // metres along the view axis; 0: |look_at - position|
  // "handedness": "left": image x grows along cross(up, forward) instead of cross(forward, up),
  // the image mirrored left to right: pbrt's cameras (a left-handed convention) seen as pbrt shows them.
  bool left_handed = false;
};

// A light keyframe: position and/or direction (aim) of a point, spot, box or directional
// light at a time in seconds. Each channel interpolates the keys that give it; a channel no
// key gives keeps the light's own value (scene/animation.cpp).
struct LightKey {
  float time = 0.0f;
  std::optional<Vec3> position;
  std::optional<Vec3> direction;  // unit
};

// Per-light settings that only the real-time pipeline reads, and the light's animation.
struct LightOptions {
  bool volumetric = true;             // takes part in volumetric lighting
  float volumetric_intensity = 1.0f;  // multiplier on its in-scattering (1 = physical)
  bool shadow = true;                 // casts shadows (shadow map in real time)
  int shadow_map_size = 1024;         // texels per side (per cube face for point lights)
  std::vector<LightKey> animation;    // increasing time; empty: still
  Interpolation interpolation = Interpolation::linear;
};

// A named entry of the scene's "media" table: what volume primitives are filled with
// (VolumePrimitive::medium) and what surfaces enclose (Material::interior).
struct NamedMedium {
  std::string name;
  VolumeShader shader;
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
// A triangle mesh from a file: OBJ (tinyobjloader), glTF 2.0 (.gltf/.glb, tinygltf), PLY or COLLADA (assimp).
struct MeshFileShape {
  std::string path;              // absolute, or relative to the working directory
  bool skip_degenerate = false;  // remove zero-area triangles instead of rejecting the file
};
// A closed mesh made on demand (geometry/mesh_generate.h): a subdivided unit sphere or a
// (2, 3) torus knot of at least `triangles` triangles (occluders of a chosen size).
struct GeneratedMeshShape {
  enum class Kind { kSphere, kTorusKnot } kind = Kind::kSphere;
  uint64_t triangles = 20;
};
// Triangles given in the scene itself ("positions", "indices", optional "normals"), as pbrt-v4's
// trianglemesh is; validated like a file's mesh. Shared: scenes are copied per frame.
struct InlineMeshShape {
  std::shared_ptr<const TriangleMesh> mesh;
};
using ShapeGeometry =
    std::variant<SphereShape, BoxShape, RectangleShape, MeshFileShape, GeneratedMeshShape, InlineMeshShape>;

struct ShapeDesc {
  ShapeGeometry geometry;
  Transform transform;   // object to world
  int material = 0;      // index into SceneDesc::materials
  SourceLocation where;  // e.g. {"room.json", "/shapes/3"}
  // A holdout (matte) object: the camera sees a hole through it (black beauty, alpha 0), as it
  // would see the background; every other ray sees its material (it shadows and reflects).
  bool holdout = false;
  // A coarse closed stand-in for the shape's shadow volumes in the hybrid (Wyman & Ramsey 2008,
  // W10), placed by the same transform; nothing else sees it. Opt-in and approximate: the
  // shafts follow the proxy's silhouette, not the shape's.
  std::optional<ShapeGeometry> proxy;
};

struct SceneDesc {
  std::string file;  // the scene file's name as given (or "builtin:NAME")
  // Every file the scene names (meshes, grids, images, IES profiles), resolved against the
  // scene file's folder, each once: what no output may replace, and what checkpoints key on.
  std::vector<std::string> files;
  // Located warnings from reading the scene (an open mesh read by parity, a pbrt-v4 directive
  // approximated): the commands print them; the render still runs.
  std::vector<std::string> warnings;
  CameraDesc camera;
  // The file's "render" object; resolution is the camera's (render_settings(SceneDesc)).
  RenderSettings render;
  // The file's "realtime" object, the defaults of `caligo realtime`; resolution is the camera's.
  RealtimeSettings realtime;
  std::vector<Material> materials;
  std::vector<ShapeDesc> shapes;
  std::vector<Light> lights;  // sphere and quad lights also become visible geometry
  // Per light, same order. May be shorter than `lights` (scenes built in code): read it
  // through options(i), which gives the defaults for a light without an entry.
  std::vector<LightOptions> light_options;
  std::vector<NamedMedium> media;
  std::vector<VolumePrimitive> volumes;

  const LightOptions& options(size_t light) const {
    static const LightOptions kDefaults;
    return light < light_options.size() ? light_options[light] : kDefaults;
  }
  // The scene at `time` seconds: camera on its path, lights at their keyframes, gobos and
  // noise advanced by their velocities. The result is still (no paths, no animation).
  SceneDesc at_time(float time) const;
  // Its parts, for a renderer that builds the still parts once (the real-time pipeline): the
  // camera on its path, the lights at their keyframes (gobos advanced), and the volumes with
  // their noise advanced by the wind; media_move() says whether the volumes change at all.
  CameraDesc camera_at(float time) const;
  std::vector<Light> lights_at(float time) const;
  std::vector<VolumePrimitive> volumes_at(float time) const;
  bool media_move() const;
  // Seconds covered by camera and light keyframes (0 for a still scene).
  float duration() const;
};

}  // namespace caligo
