// The closed set of light types, as a std::variant of plain value types.
//
// Units (see docs/scene-format.md): point and spot lights carry intensity in W/sr,
// area lights (sphere, quad, mesh triangles) radiance in W m^-2 sr^-1, the directional
// light irradiance in W m^-2 on a surface facing it, the environment radiance.
// Scene loading converts powers (W) into these before a light is built.
//
// To add a light type, define its struct here and add it to `Light`; the compiler then names
// each place that must handle it, because every visitor over `Light` (but shaded_light,
// below) has one overload per member and no `auto` catch-all. Measured (2026-12, a disk light
// added to the variant and compiled) for a path-traced light:
//   lights/light.cpp         is_delta, is_infinite, power, light_centre, light_type_name,
//                            pose_light (keyframes), set_scene_radius
//   lights/light_sample.cpp  sample_light, light_pdf, escaped_radiance (a delta light also
//                            gets a delta_arrival in light_profile.h)
//   lights/light_reach.h/.cpp  where it can light a ray (LightReach)
//   lights/light_tree.cpp    its bounds in the light tree
//   scene/scene.cpp          the visible geometry of an area light
//   scene/light_parser.cpp   its scene-file "type" (not named by the compiler)
// The real-time passes need nothing: realtime/frame_light.h's shaded_light leaves a type it
// does not know to the path tracer. To shade it in real time too, add it to ShadedLight; the
// compiler then names each pass.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <variant>
#include <vector>

#include "core/bounds.h"
#include "core/math.h"
#include "core/rgb.h"
#include "core/vec.h"

namespace caligo {

class GoboImage;   // lights/gobo.h
class IesProfile;  // lights/ies.h
class EnvironmentMap;  // lights/environment_map.h

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
};

// A spherical emitter, sampled by the cone it subtends (uniform area sampling from inside).
// Emits outwards only, unless two_sided (then also into its interior).
struct SphereLight {
  Vec3 center;
  float radius = 1.0f;
  RGB radiance;
  bool two_sided = false;
};

// A parallelogram corner + s*edge1 + t*edge2, s,t in [0,1]. Emits on the side of
// normalize(cross(edge1, edge2)) only, unless two_sided.
struct QuadLight {
  Vec3 corner, edge1, edge2;
  RGB radiance;
  bool two_sided = false;
};

// Light from a distant disk (the sun) of the given angular radius; radius 0 is a delta
// direction. `direction` is the way the light travels (from the light towards the scene).
struct DirectionalLight {
  Vec3 direction;
  RGB irradiance;  // W/m^2 on a surface perpendicular to `direction`
  float cos_angular_radius = 1.0f;
  float scene_radius = 1.0f;  // set by the scene builder, for power()
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
};

// One emissive triangle (from a shape with an emissive material). Emits on the side of
// its geometric normal cross(p1 - p0, p2 - p0) unless two_sided.
struct TriangleLight {
  Vec3 p0, p1, p2;
  RGB radiance;
  bool two_sided = false;
};

using Light = std::variant<PointLight, SpotLight, SphereLight, QuadLight, DirectionalLight, EnvironmentLight,
                           TriangleLight, BoxLight>;

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
void pose_light(Light& light, std::optional<Vec3> position, std::optional<Vec3> direction, float time);
// Lights at infinity need the scene's radius for power(); the others ignore it.
void set_scene_radius(Light& light, float radius);

}  // namespace caligo
