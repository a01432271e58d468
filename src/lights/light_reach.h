// Where along a ray a light can send any light at all. Outside it the in-scattered light of
// this light is exactly zero, so a distance pdf that is zero there stays unbiased, and a
// march that skips it skips nothing:
//
//   spot light     one nappe of its outer cone (smoothstep(cos_outer, ...) is 0 outside), cut
//                  by its range sphere when the range is finite;
//   point light    its range sphere (the windowed falloff is 0 beyond), else everything;
//   box light      its oriented box (light_box below);
//   quad, triangle the open half-space in front of the emitting face unless two-sided;
//   others         the whole segment (sphere lights emit in every direction; directional and
//                  environment lights light everything).
//
// The path tracer restricts equiangular sampling to it (integrators/volume_direct.cpp); the
// real-time passes march only inside it (realtime/light_volume.h). The solids are
// core/ray_solids.h's; each type's reach() is in lights/types/. Pure and thread-safe.
#pragma once

#include <optional>

#include "core/ray_range.h"
#include "core/ray_solids.h"
#include "core/vec.h"
#include "lights/light.h"

namespace caligo {

// The part of [tmin, tmax] of origin + t dir (dir unit) that a light can reach (table above),
// for one light type, a Light or a narrower variant of them (the real-time passes' ShadedLight).
template <typename AnyLight>
std::optional<RayRange> light_reach(const AnyLight& light, Vec3 origin, Vec3 dir, float tmin, float tmax) {
  if constexpr (requires { light.reach(origin, dir, tmin, tmax); })
    return light.reach(origin, dir, tmin, tmax);
  else
    return std::visit([&](const auto& l) { return l.reach(origin, dir, tmin, tmax); }, light);
}

// The box a box light fills: right = cross(direction, up), |local x| <= half_width,
// |local y| <= half_height, 0 <= local z <= range along `direction` from `position`.
OrientedBox light_box(const BoxLight& light);

}  // namespace caligo
