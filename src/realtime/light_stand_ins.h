// What the real-time passes shade in place of the lights they cannot shade as they are: area
// lights and the environment become the delta lights every pass already handles, so that no
// pass grows a case per emitter shape and a stand-in gets shadow maps, gobo-free profiles,
// media transmittance and both volumetric methods for free.
//
// Area lights (sphere, quad, disk, triangle) become a point light at the emitter's centre
// with its far-field intensity: a sphere of radiance L and radius r emits I = L pi r^2 in
// every direction; a flat emitter of area A emits I(theta) = L A cos(theta) about its normal
// (|cos| when two-sided), carried by a tabulated IES profile along the normal. The sphere's
// is exact on surfaces that see all of it; in fog at distance d the point falls short of the
// sphere's solid angle by x^2 / (2 (1 - sqrt(1 - x^2))) with x = r / d (-6.7 % at d = 2r,
// -1.6 % at d = 4r). A disk's on-axis irradiance is L pi R^2 / (R^2 + d^2), which the point
// overstates by (R/d)^2: flat stand-ins are exact from afar only. The shadow is the point's
// (hard); the emitter's own geometry is left out of its shadow map.
//
// The environment becomes `count` directional lights by median cut (Debevec 2006, "A Median
// Cut Algorithm for Light Probe Sampling"): the lat-long radiance is split, region by region,
// into parts of equal luminance times solid angle along their longer side, and each part is a
// sun from its luminance-weighted mean direction m / |m|. The first cut is the horizon. A
// surface that sees all of a part receives E (n . m) from it, with E the part's integral of
// radiance: the sun's irradiance is E |m|, and its in-scattering is scaled by 1 / |m| so the fog
// receives E (exact for an isotropic phase function). Unshadowed, an upward surface under a
// constant sky and isotropic fog anywhere are then exact for any count; shadow maps from each
// part give the sky-visibility term (soft for many parts, banded for few).
#pragma once

#include <vector>

#include "lights/light.h"

namespace caligo {

PointLight stand_in(const SphereLight& light);
PointLight stand_in(const QuadLight& light);
PointLight stand_in(const DiskLight& light);
PointLight stand_in(const TriangleLight& light);

// One part of the environment: the sun (direction: the way the light travels) and the factor
// on its in-scattering, 1 / |m| >= 1.
struct EnvironmentSun {
  DirectionalLight light;
  float volumetric_scale = 1.0f;
};
// At most `count` (>= 1) suns, fewer when the map has fewer non-black cells; the sum of
// irradiance * volumetric_scale is the environment's integral of radiance.
std::vector<EnvironmentSun> environment_stand_ins(const EnvironmentLight& light, int count);

}  // namespace caligo
