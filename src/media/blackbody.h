// Blackbody (Planckian) emission for fire and other hot media: the colour of a blackbody at
// a temperature, and the magnitude of its radiance.
//
// Colour: Planck's law B(lambda, T) integrated against the CIE 1931 2-degree colour-matching
// functions (the CIE's tabulated data, 360-830 nm at 5 nm), giving XYZ; XYZ goes to linear
// Rec.709 (sRGB primaries, D65 white) by the standard matrix. Below about 1900 K the
// Planckian locus leaves the Rec.709 gamut (blue turns negative; below about 900 K green
// too): negative components are clamped to 0, and the colour is then renormalised so that
// its Rec.709 luminance (RGB::luminance) is exactly 1. The clamp keeps hue and
// brightness believable instead of emitting negative light; it shifts the colour
// towards the gamut edge, so low temperatures are slightly more saturated red than
// the true chromaticity (which no Rec.709 display can show anyway).
//
// Magnitude: blackbody_exitance_radiance is the total (all-wavelength) radiance of a
// blackbody, sigma_SB T^4 / pi in W m^-2 sr^-1 (Stefan-Boltzmann's exitance over pi, as
// a Lambertian emitter). Emission = intensity * blackbody_color(T) *
// blackbody_exitance_radiance(T) is the convention of Cycles' Principled Volume with
// "blackbody intensity 1", except that Cycles also multiplies by 1e-6 (its kernel scales
// sigma_SB by 1e-6), so a scene matched to Cycles sets intensity 1e-6. Note that this is
// the total radiance carried in a luminance-1 colour, not the visible (photometric) part:
// a 1000 K body is far dimmer to the eye than sigma T^4 / pi suggests.
//
// Thread safety: blackbody_color builds its table once, on first use (a function-local
// static, so concurrent first calls are safe); afterwards every call is a read-only lookup.
#pragma once

#include "core/rgb.h"

namespace caligo {

// CIE 1931 XYZ tristimulus values.
struct Xyz {
  double x = 0, y = 0, z = 0;
};

// The colour of a blackbody at `kelvin` as linear Rec.709 RGB with luminance 1, clamped to
// the gamut as described above. Cheap (a table lookup with linear interpolation in 1/T,
// exact at the table's nodes); within 1e-3 of blackbody_color_direct for every T > 0.
// T <= 0 or NaN gives black. The table spans 500 K to infinity (it is uniform in 1/T, and
// 1/T = 0 is its first node); below 500 K it returns the 500 K colour, pure Rec.709 red
// (1/0.2126, 0, 0), which is exactly what the clamp gives at every T below about 900 K.
RGB blackbody_color(float kelvin);

// sigma_SB * T^4 / pi in W m^-2 sr^-1; 0 for T <= 0 or NaN.
float blackbody_exitance_radiance(float kelvin);

// ---- The exact computations behind the table (slow: for tests and table building) -------

// Planck's spectral radiance B(lambda, T) in W m^-2 sr^-1 per metre of wavelength.
double planck_spectral_radiance(double wavelength_m, double kelvin);

// The blackbody's XYZ by direct summation over the 5 nm CIE table, scaled to Y = 1.
// Requires kelvin > 0.
Xyz blackbody_xyz(double kelvin);

// XYZ to linear Rec.709 (D65) with no clamping; the inverse of rec709_to_xyz.
RGB xyz_to_linear_rec709(const Xyz& xyz);
Xyz rec709_to_xyz(RGB rgb);

// blackbody_color computed directly (integration, conversion, clamp, renormalisation)
// without the table. Requires kelvin > 0.
RGB blackbody_color_direct(double kelvin);

}  // namespace caligo
