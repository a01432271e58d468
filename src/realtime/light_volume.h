// Light volumes of the real-time accumulation (the seed's "render light geometry"): the
// stretch of a camera ray where a light can contribute at all. Point lights are bounded by
// their range sphere, spot lights by one nappe of their outer cone cut by the range sphere,
// box lights by their oriented box, directional lights not at all. Marching only inside
// these intervals is what makes many small lights cheap.
//
// All functions take a unit direction and return the interval of t (metres along the ray)
// within [tmin, tmax]; std::nullopt when it is empty. Pure and thread-safe.
#pragma once

#include <optional>

#include "core/vec.h"
#include "lights/light.h"
#include "realtime/view.h"

namespace caligo {

struct TInterval {
  float t0, t1;  // t0 <= t1
};

// Overlap of a ray with the ball |p - centre| <= radius.
std::optional<TInterval> ray_sphere_interval(Vec3 origin, Vec3 dir, Vec3 centre, float radius, float tmin,
                                             float tmax);

// Overlap with the convex cone {p : dot(p - apex, axis) >= cos_half |p - apex|} (one nappe,
// unbounded). cos_half <= 0 (half-angle >= 90 degrees) is not convex; it returns the whole
// [tmin, tmax] (a conservative bound: the march then skips nothing but stays correct).
std::optional<TInterval> ray_cone_interval(Vec3 origin, Vec3 dir, Vec3 apex, Vec3 axis, float cos_half,
                                           float tmin, float tmax);

// Overlap with a box light's box: right = cross(direction, up), |local x| <= half_width,
// |local y| <= half_height, 0 <= local z <= range, local z along `direction` from `position`.
std::optional<TInterval> ray_box_light_interval(Vec3 origin, Vec3 dir, const BoxLight& light, float tmin,
                                                float tmax);

// Where on the ray `light` can light the medium: the interval above for point (range
// sphere; infinite range: everything), spot (cone and range sphere) and box lights, all of
// [tmin, tmax] for a directional light, std::nullopt for lights the real-time passes do not
// march (area and environment lights).
std::optional<TInterval> light_volume_interval(const Light& light, Vec3 origin, Vec3 dir, float tmin,
                                               float tmax);

// Pixels [x0, x1) x [y0, y1) of `view` whose rays can meet the light's volume: the
// projected bounding corners of the volume (the seed rasterises the light geometry for the
// same purpose). Conservative: the whole image when a corner lies behind the eye, or for
// directional lights and infinite ranges. Empty (x0 >= x1) when the volume is off screen.
struct PixelRect {
  int x0, y0, x1, y1;
};
PixelRect light_screen_bounds(const Light& light, const View& view);

}  // namespace caligo
