// The closed set of light types, as a std::variant of plain value types.
//
// Units (see docs/scene-format.md): point and spot lights carry intensity in W/sr,
// area lights (sphere, quad, mesh triangles) radiance in W m^-2 sr^-1, the directional
// light irradiance in W m^-2 on a surface facing it, the environment radiance.
// Scene loading converts powers (W) into these before a light is built.
//
// Every type declares the same members (CALIGO_EMITTER below) and defines all of its
// behaviour in one file, lights/types/<type>.cpp; the functions over `Light` at the end of
// this header and in light_sample.h, light_reach.h and light_tree.h only dispatch to them.
// To add a light type:
//   lights/light.h                its struct, with CALIGO_EMITTER, in `Light`
//   lights/types/<type>.cpp       its members (the build finds the file by itself)
//   scene/light_parser.cpp        its scene-file "type" and fields
// The compiler names a missing member (the Emitter concept in light.cpp) and the linker a
// declared one left undefined. The real-time passes need nothing: realtime/frame_light.h's
// shaded_light leaves a type it does not know to the path tracer. To shade it in real time
// too, add it to ShadedLight; the compiler then names each pass. Measured 2026-12 with a disk
// light: these three files, nothing else.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <variant>
#include <vector>

#include "core/bounds.h"
#include "core/math.h"
#include "core/ray_range.h"
#include "core/rgb.h"
#include "core/vec.h"

namespace caligo {

class GoboImage;   // lights/gobo.h
class IesProfile;  // lights/ies.h
class EnvironmentMap;  // lights/environment_map.h
struct LightSample;    // lights/light_sample.h
struct LightBounds;    // lights/light_tree.h
struct LightGeometry;  // below

// Where and when an animation puts a light (SceneDesc's keyframes): a position and a
// direction where the keyframes give them, and the time its gobo has scrolled and spun for.
struct LightPose {
  std::optional<Vec3> position, direction;
  float time = 0.0f;
};

// What every light type declares; each member is defined in lights/types/<type>.cpp.
//   kTypeName  the scene file's "type"
//   kInfinite  at infinity: reached by rays leaving the scene, powered by the scene's radius
//   is_delta   no area or solid angle (a BSDF-sampled ray never hits it)
//   power      emitted watts, only for choosing lights (light_tree.h, light_sampler.h)
//   centre     the point equiangular sampling aims at, if the light has one
//   pose       placed at a LightPose (types that do not animate ignore it)
//   sample, pdf, escaped   next-event estimation and MIS (light_sample.h)
//   reach      where along a ray it can light anything (light_reach.h)
//   bounds     its bounds in the light tree; nullopt at infinity (light_tree.h)
//   surface    the geometry camera and bounce rays hit, for area lights (LightGeometry)
#define CALIGO_EMITTER(type_name, infinite)                                                          \
  static constexpr const char* kTypeName = type_name;                                                \
  static constexpr bool kInfinite = infinite;                                                        \
  bool is_delta() const;                                                                             \
  float power() const;                                                                               \
  std::optional<Vec3> centre() const;                                                                \
  void pose(const LightPose& at);                                                                    \
  std::optional<LightSample> sample(Vec3 receiver, Vec2 u) const;                                    \
  float pdf(Vec3 receiver, Vec3 wi, Vec3 on_light, Vec3 light_normal) const;                         \
  RGB escaped(Vec3 w) const;                                                                         \
  std::optional<RayRange> reach(Vec3 origin, Vec3 dir, float tmin, float tmax) const;                \
  std::optional<LightBounds> bounds() const;                                                         \
  std::optional<LightGeometry> surface() const

// A projector texture (gobo, cookie) that multiplies a spot or box light's emission by the
// colour at a texture coordinate. Texture coordinates are rotated by `rotation` about the
// image centre, then shifted by `offset` (both in texture units, wrapping). `scroll` and
// `spin` animate them (per second); SceneDesc::at_time folds them into offset and rotation.
struct Gobo {
  std::shared_ptr<const GoboImage> image;  // null: no gobo
  Vec2 offset;
  float rotation = 0.0f;  // radians
  Vec2 scroll;            // texture units per second
  float spin = 0.0f;      // radians per second
};

// A photometric (IES LM-63) intensity profile. Vertical angle 0 points along `axis`
// (photometric nadir); horizontal angle 0 lies along Frame::from_z(axis).s.
struct IesAttachment {
  std::shared_ptr<const IesProfile> profile;  // null: no profile
  Vec3 axis{0.0f, -1.0f, 0.0f};               // unit
};

// The windowed inverse square of game engines: emission is scaled by
// (1 - (d / range)^4)^2 for d < range and 0 beyond, so the light's influence is a bounded
// sphere (the seed's "attenuation range"). range = infinity keeps the pure inverse square.
struct PointLight {
  Vec3 position;
  RGB intensity;  // W/sr
  float range = kInfinity;
  IesAttachment ies;

  CALIGO_EMITTER("point", false);
};

// Smooth falloff between the inner and outer cone (smoothstep in cos theta), as in pbrt-v4.
// The gobo is projected through the outer cone: the square texture spans tan(outer angle).
struct SpotLight {
  Vec3 position;
  Vec3 direction;  // unit, the cone axis
  float cos_inner = 1.0f;
  float cos_outer = 0.0f;
  RGB intensity;  // W/sr on the axis
  float range = kInfinity;
  Vec3 up{0.0f, 1.0f, 0.0f};  // unit, perpendicular to direction: the gobo's +v axis
  Gobo gobo;
  IesAttachment ies;

  CALIGO_EMITTER("spot", false);
};

// The seed's "box light": parallel light filling an oriented box. The emitting face is the
// rectangle centred at `position`, spanned by right * [-half_width, half_width] and
// up * [-half_height, half_height] with right = cross(direction, up); light travels along
// `direction` for `range` metres and stops there.
// A delta light: every point inside the box receives `irradiance` from -direction.
// The gobo maps the emitting face to [0,1]^2.
struct BoxLight {
  Vec3 position;
  Vec3 direction;  // unit
  Vec3 up;         // unit, perpendicular to direction
  float half_width = 1.0f, half_height = 1.0f;
  float range = 10.0f;
  RGB irradiance;  // W/m^2 on a surface facing the light
  Gobo gobo;

  CALIGO_EMITTER("box", false);
};

// A spherical emitter, sampled by the cone it subtends (uniform area sampling from inside).
// Emits outwards only, unless two_sided (then also into its interior).
struct SphereLight {
  Vec3 center;
  float radius = 1.0f;
  RGB radiance;
  bool two_sided = false;

  CALIGO_EMITTER("sphere", false);
};

// A parallelogram corner + s*edge1 + t*edge2, s,t in [0,1]. Emits on the side of
// normalize(cross(edge1, edge2)) only, unless two_sided.
struct QuadLight {
  Vec3 corner, edge1, edge2;
  RGB radiance;
  bool two_sided = false;

  CALIGO_EMITTER("quad", false);
};

// A disk of uniform radiance, emitting on the side of `normal` unless two_sided. It is a
// regular kSides-gon inscribed in the circle, so that the geometry rays hit and the area that
// is sampled are the same shape; its area is 0.16 % below pi r^2 (scene files that give a
// power divide by the polygon's area, so the power is exact).
struct DiskLight {
  static constexpr int kSides = 64;
  Vec3 center;
  Vec3 normal{0.0f, 0.0f, 1.0f};  // unit
  float radius = 1.0f;
  RGB radiance;
  bool two_sided = false;

  float area() const;     // of the polygon
  Vec3 vertex(int k) const;  // k in [0, kSides], counter-clockwise about `normal`; k = kSides is 0
  CALIGO_EMITTER("disk", false);
};

// Light from a distant disk (the sun) of the given angular radius; radius 0 is a delta
// direction. `direction` is the way the light travels (from the light towards the scene).
struct DirectionalLight {
  Vec3 direction;
  RGB irradiance;  // W/m^2 on a surface perpendicular to `direction`
  float cos_angular_radius = 1.0f;
  float scene_radius = 1.0f;  // set by the scene builder, for power()

  CALIGO_EMITTER("directional", true);
};

// Radiance arriving from every direction not blocked by the scene: `radiance` alone, or
// `radiance` times an image (lights/environment_map.h, lat-long) turned about +Y by the
// rotation (world = R_y(angle) * map; angle > 0 turns +Z towards +X).
// `visible` = false hides it from camera rays and from rays after only specular events
// (what the camera sees through glass and in mirrors); lighting is unchanged.
struct EnvironmentLight {
  RGB radiance;               // the constant radiance, or the map's scale
  float scene_radius = 1.0f;  // set by the scene builder, for power()
  std::shared_ptr<const EnvironmentMap> map;  // null: constant
  float cos_rotation = 1.0f, sin_rotation = 0.0f;
  bool visible = true;

  CALIGO_EMITTER("environment", true);
};

// One emissive triangle (from a shape with an emissive material). Emits on the side of
// its geometric normal cross(p1 - p0, p2 - p0) unless two_sided.
struct TriangleLight {
  Vec3 p0, p1, p2;
  RGB radiance;
  bool two_sided = false;

  CALIGO_EMITTER("triangle", false);
};

// The surface an area light shows to camera and bounce rays: a sphere, or triangles (indices
// into positions, three per triangle, wound so that cross(p1 - p0, p2 - p0) is the emitting
// side). The scene gives it a black material emitting `radiance`.
struct VisibleSphere {
  Vec3 centre;
  float radius;
};
struct VisibleTriangles {
  std::vector<Vec3> positions;
  std::vector<uint32_t> indices;
};
struct LightGeometry {
  RGB radiance;
  bool two_sided = false;
  std::variant<VisibleSphere, VisibleTriangles> shape;
};

using Light = std::variant<PointLight, SpotLight, SphereLight, QuadLight, DirectionalLight, EnvironmentLight,
                           TriangleLight, BoxLight, DiskLight>;

// True for lights with no area or solid angle (a BSDF-sampled ray can never hit them).
bool is_delta(const Light& light);
// True for lights at infinity (reached by rays that leave the scene).
bool is_infinite(const Light& light);
// Total emitted power in W (for choosing lights in proportion to power).
float power(const Light& light);
// The point equiangular sampling aims at, for lights that have one. Parallel light (box,
// directional) and the environment have none: their in-scattering does not peak near a point,
// so density sampling serves them.
std::optional<Vec3> light_centre(const Light& light);
// The type's name as a scene file's "type" gives it ("point", "spot", ...).
const char* light_type_name(const Light& light);
// Poses a light at `time` seconds of its animation: the keyframed position and direction
// (either may be absent; a new direction keeps `up` perpendicular), and its gobo's scroll and
// spin folded into offset and rotation. Area lights and the environment do not animate (the
// scene parser rejects "animation" on them).
void pose_light(Light& light, const LightPose& at);
// Lights at infinity need the scene's radius for power(); the others ignore it.
void set_scene_radius(Light& light, float radius);
// The geometry of an area light; nullopt for the others.
std::optional<LightGeometry> visible_geometry(const Light& light);

}  // namespace caligo
