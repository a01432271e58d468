// Where along a ray a light can send any light at all: the interval equiangular sampling is
// restricted to (integrators/volume_direct.cpp). Outside it the in-scattered light of this
// light is exactly zero, so a distance pdf that is zero there stays unbiased.
//
//   spot light     one nappe of its outer cone (smoothstep(cos_outer, ...) is 0 outside), cut
//                  by its range sphere when the range is finite;
//   point light    its range sphere (the windowed falloff is 0 beyond), else everything;
//   quad, triangle the open half-space in front of the emitting face unless two-sided;
//   others         the whole segment (sphere lights emit in every direction; box,
//                  directional and environment lights have no equiangular centre anyway).
//
// The same geometry as realtime/light_volume.h's ray_cone_interval, written again here so
// that the integrators do not depend on the real-time pipeline. Pure and thread-safe.
#pragma once

#include <optional>

#include "core/vec.h"
#include "lights/light.h"

namespace caligo {

struct RayInterval {
  float t0, t1;  // t0 <= t1
};

// The part of [tmin, tmax] where origin + t * dir (dir unit) lies in the cone
// {p : dot(p - apex, axis) >= cos_half |p - apex|}; a half-angle of 90 degrees or more
// (cos_half <= 0) returns all of [tmin, tmax] (conservative). std::nullopt when empty.
std::optional<RayInterval> ray_cone_reach(Vec3 origin, Vec3 dir, Vec3 apex, Vec3 axis, float cos_half,
                                          float tmin, float tmax);

// The part of [tmin, tmax] within `radius` of `centre`.
std::optional<RayInterval> ray_ball_reach(Vec3 origin, Vec3 dir, Vec3 centre, float radius, float tmin,
                                          float tmax);

// The part of [tmin, tmax] where dot(p - on_plane, normal) > 0.
std::optional<RayInterval> ray_half_space_reach(Vec3 origin, Vec3 dir, Vec3 on_plane, Vec3 normal, float tmin,
                                                float tmax);

// The part of [tmin, tmax] that `light` can reach (table above).
std::optional<RayInterval> light_reach(const Light& light, Vec3 origin, Vec3 dir, float tmin, float tmax);

}  // namespace caligo
