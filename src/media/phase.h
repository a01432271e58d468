// Phase functions: the closed set of angular scattering distributions of a medium.
//
// Convention: `wo` is the direction the light travels BEFORE scattering (the ray's
// direction of propagation at the scattering point) and `wi` the direction it travels AFTER.
// cos_theta = dot(wo, wi), so cos_theta = 1 is forward scattering and g > 0 favours it.
// Every phase function here integrates to 1 over the sphere and is sampled exactly, so the
// pdf of phase_sample equals phase_eval.
//
// To add a phase function: define its struct, add it to PhaseFunction, overload the
// functions in phase.cpp, and add it to phase_test.cpp's normalisation and chi^2 tests.
#pragma once

#include <variant>

#include "core/vec.h"

namespace caligo {

struct IsotropicPhase {};

// Henyey & Greenstein 1941. g in (-1, 1) is the mean cosine.
struct HenyeyGreensteinPhase {
  float g = 0.0f;
};

// Schlick's rational approximation of HG (Blasi, Le Saec & Schlick 1993), as used in
// real-time engines: p = (1 - k^2) / (4 pi (1 - k cos_theta)^2), k in (-1, 1), k > 0
// favouring forward scattering; k = 1.55 g - 0.55 g^3 approximates HG(g).
struct SchlickPhase {
  float k = 0.0f;  // in (-1, 1)
  static SchlickPhase from_g(float g) { return {1.55f * g - 0.55f * g * g * g}; }
};

// A mix of two HG lobes: w * HG(g1) + (1 - w) * HG(g2) (e.g. forward + back scattering in clouds).
struct DoubleHenyeyGreensteinPhase {
  float g1 = 0.5f, g2 = -0.3f;
  float w = 0.7f;  // weight of the first lobe, in [0, 1]
};

using PhaseFunction =
    std::variant<IsotropicPhase, HenyeyGreensteinPhase, SchlickPhase, DoubleHenyeyGreensteinPhase>;

struct PhaseSample {
  Vec3 wi;
  float pdf;  // solid angle; equal to phase_eval(wo, wi)
};

// Value of the phase function (1/sr) for travel direction wo scattering into wi.
float phase_eval(const PhaseFunction& phase, Vec3 wo, Vec3 wi);
// Samples wi given wo; u in [0,1)^2.
PhaseSample phase_sample(const PhaseFunction& phase, Vec3 wo, Vec2 u);
float phase_pdf(const PhaseFunction& phase, Vec3 wo, Vec3 wi);
// Mean cosine (g) of the distribution, for diagnostics and approximations.
float phase_mean_cosine(const PhaseFunction& phase);

// The same as functions of cos_theta only, for tests and real-time code.
float henyey_greenstein(float cos_theta, float g);
float schlick(float cos_theta, float k);

}  // namespace caligo
