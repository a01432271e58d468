// A procedural sky with a sun, as an environment map (lights/environment_map.h), for scenes
// that cannot ship an HDR image (the hdri-fog built-in): generated in memory at scene load,
// so no file is needed and the result does not depend on the working directory.
//
// Not a physical sky model (no Preetham or Hosek-Wilkie fit): a blue gradient from the
// zenith to a paler horizon, a glow around the sun, a sun disk, and a uniform brownish
// ground below the horizon (blended over +-1 degree). The sun's colour is the transmittance
// exp(-tau * m) of a fixed optical depth tau = (0.08, 0.14, 0.30) along the Kasten-Young
// (1989) relative air mass m, so a low sun is orange; the sky dims as the sun sets.
// The sun disk is normalised so that its irradiance on a surface facing it is exactly
// kSkySunIrradiance * exp(-tau * m), whatever the resolution (pixels are partly covered
// according to 16 x 16 sub-samples). Deterministic; linear RGB.
#pragma once

#include "core/rgb.h"
#include "core/vec.h"
#include "lights/environment_map.h"

namespace caligo {

inline constexpr int kMinSkyResolution = 16;
inline constexpr int kMaxSkyResolution = 8192;
inline constexpr float kSkySunIrradiance = 20.0f;  // W/m^2 facing the sun, before the air's colour

struct SkyParameters {
  int resolution = 512;            // the map's width; its height is half of it
  float sun_elevation = 30.0f;     // degrees above the horizon, in [0, 90]
  float sun_azimuth = 0.0f;        // degrees: 0 puts the sun towards -Z, 90 towards +X
  float sun_angular_radius = 0.5f; // degrees, in [0.05, 10] (the real sun: 0.27)
};

// The unit direction towards the sun's centre (the map's frame).
Vec3 sky_sun_direction(const SkyParameters& p);
// The sun's irradiance on a surface facing it: kSkySunIrradiance times the air's transmittance.
RGB sky_sun_irradiance(const SkyParameters& p);

// Throws std::invalid_argument for parameters outside the ranges above.
EnvironmentMap generate_sky(const SkyParameters& p);

}  // namespace caligo
