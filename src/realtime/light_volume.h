// Light volumes of the real-time accumulation (the seed's "render light geometry"): the
// stretch of a camera ray where a light can contribute at all. Point lights are bounded by
// their range sphere, spot lights by one nappe of their outer cone cut by the range sphere,
// box lights by their oriented box, directional lights not at all. Marching only inside
// these intervals is what makes many small lights cheap.
//
// The ranges take a unit direction and return the interval of t (metres along the ray)
// within [tmin, tmax]; std::nullopt when it is empty. Pure and thread-safe.
#pragma once

#include <optional>

#include "core/ray_range.h"
#include "core/vec.h"
#include "lights/light_reach.h"
#include "realtime/frame_light.h"
#include "realtime/view.h"

namespace caligo {

// Where on the ray `light` can light the medium: lights/light_reach.h's range.
inline std::optional<RayRange> light_volume_interval(const ShadedLight& light, Vec3 origin, Vec3 dir, float tmin,
                                                     float tmax) {
  return light_reach(light, origin, dir, tmin, tmax);
}

// Pixels [x0, x1) x [y0, y1) of `view` whose rays can meet the light's volume: the
// projected bounding corners of the volume (the seed rasterises the light geometry for the
// same purpose). Conservative: the whole image when a corner lies behind the eye, or for
// directional lights and infinite ranges. Empty (x0 >= x1) when the volume is off screen.
struct PixelRect {
  int x0, y0, x1, y1;
};
PixelRect light_screen_bounds(const ShadedLight& light, const View& view);

}  // namespace caligo
