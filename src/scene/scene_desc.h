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
#include "settings/path_settings.h"
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

// Defaults of `caligo realtime` (each is also a command-line option).
struct RealtimeDefaults {
  int scale = 4;              // accumulation at 1/scale resolution: 1, 2 (half) or 4 (quarter)
  int tile_size = 8;          // interleaved-sampling tile side (tile_size^2 offsets)
  int samples = 16;           // march steps per pixel per light
  int gather_radius = 7;      // bilateral gather taps each side (2r + 1 per pass)
  float gather_depth_falloff = 1000.0f;  // weight exp(-falloff * |relative depth difference|)
  bool temporal = true;       // temporal reprojection
  float temporal_blend = 0.1f;  // weight of the current frame in the history blend
  float multiple_scattering_floor = 0.0f;  // faked multiple scattering: min shadow term
  bool equiangular_steps = false;          // "steps": "equiangular" (point and spot lights)
  float fps = 30.0f;          // frame i is at time i / fps
  int frames = 60;
};

// A pixel reconstruction filter as the scene file gives it; render/pixel_filter.h builds and
// samples it. Radius in pixels (the support is [-radius, radius]^2; Cycles' "filter width"
// is 2 x radius); sigma (gaussian only) in pixels.
enum class PixelFilterType { box, gaussian, blackman_harris };
inline constexpr std::array<EnumName<PixelFilterType>, 4> kPixelFilterNames{
    {{PixelFilterType::box, "box"},
     {PixelFilterType::gaussian, "gaussian"},
     {PixelFilterType::blackman_harris, "blackman_harris"},
     {PixelFilterType::blackman_harris, "blackman-harris"}}};
struct PixelFilterDesc {
  PixelFilterType type = PixelFilterType::box;
  float radius = 0.5f;
  float sigma = 0.5f;
  // The radius a type gets when none is given: box 0.5 (the whole pixel, today's jitter),
  // gaussian 1.5 (pbrt-v4's default, with sigma 0.5), Blackman-Harris 0.75 (Cycles' default
  // filter width of 1.5 pixels).
  static float default_radius(PixelFilterType type) {
    return type == PixelFilterType::box ? 0.5f : (type == PixelFilterType::gaussian ? 1.5f : 0.75f);
  }
};

struct RenderDefaults {
  int spp = 16;
  PathLimits limits;  // "max_bounces" (alias "max_depth") and "max_volume_bounces"
  uint64_t seed = 0;
  // Shadow rays pass through dielectrics of priority other than Off, attenuated by the media
  // the priority rules put them in (approximate caustics; lights inside glass or water).
  // Off: those dielectrics block shadow rays like any other. Null medium boundaries never block.
  bool priority_shadows = false;
  PixelFilterDesc filter;  // "filter": how samples spread over pixels (render/pixel_filter.h)
  CropWindow crop;         // "crop": the part of the image rendered (core/crop_window.h)
  // "aovs": the outputs besides the beauty, as AovSet::bits() (settings/aov.h, which this header
  // does not include); none: AovSet::defaults().
  std::optional<uint32_t> aovs;
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
using ShapeGeometry = std::variant<SphereShape, BoxShape, RectangleShape, MeshFileShape, GeneratedMeshShape>;

struct ShapeDesc {
  ShapeGeometry geometry;
  Transform transform;   // object to world
  int material = 0;      // index into SceneDesc::materials
  SourceLocation where;  // e.g. {"room.json", "/shapes/3"}
  // A holdout (matte) object: the camera sees a hole through it (black beauty, alpha 0), as it
  // would see the background; every other ray sees its material (it shadows and reflects).
  bool holdout = false;
};

struct SceneDesc {
  std::string file;  // the scene file's name as given (or "builtin:NAME")
  CameraDesc camera;
  RenderDefaults render;
  RealtimeDefaults realtime;
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
  // Seconds covered by camera and light keyframes (0 for a still scene).
  float duration() const;
};

}  // namespace caligo
