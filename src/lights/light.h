// The closed set of light types, as a std::variant of plain value types.
//
// Units (see docs/scene-format.md): point and spot lights carry intensity in W/sr,
// area lights (sphere, quad, mesh triangles) radiance in W m^-2 sr^-1, the directional
// light irradiance in W m^-2 on a surface facing it, the environment radiance.
// Scene loading converts powers (W) into these before a light is built.
//
// To add a light type: define its struct here, add it to `Light`, and give it an overload
// of each free function in light_sample.h / light.cpp (sample_li, pdf_li, le, power).
#pragma once

#include <cstdint>
#include <variant>
#include <vector>

#include "core/bounds.h"
#include "core/rgb.h"
#include "core/vec.h"

namespace caligo {

struct PointLight {
  Vec3 position;
  RGB intensity;  // W/sr
};

// Smooth falloff between the inner and outer cone (smoothstep in cos theta), as in pbrt-v4.
struct SpotLight {
  Vec3 position;
  Vec3 direction;  // unit, the cone axis
  float cos_inner = 1.0f;
  float cos_outer = 0.0f;
  RGB intensity;  // W/sr on the axis
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

// Radiance arriving from every direction not blocked by the scene.
struct EnvironmentLight {
  RGB radiance;
  float scene_radius = 1.0f;  // set by the scene builder, for power()
};

// One emissive triangle (from a shape with an emissive material). Emits on the side of
// its geometric normal cross(p1 - p0, p2 - p0) unless two_sided.
struct TriangleLight {
  Vec3 p0, p1, p2;
  RGB radiance;
  bool two_sided = false;
};

using Light = std::variant<PointLight, SpotLight, SphereLight, QuadLight, DirectionalLight, EnvironmentLight,
                           TriangleLight>;

// True for lights with no area or solid angle (a BSDF-sampled ray can never hit them).
bool is_delta(const Light& light);
// True for lights at infinity (reached by rays that leave the scene).
bool is_infinite(const Light& light);
// Total emitted power in W (for choosing lights in proportion to power).
float power(const Light& light);

}  // namespace caligo
