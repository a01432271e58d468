// Hoffman and Preetham's in-scattering over a ray interval (2002, "Rendering Outdoor Light
// Scattering in Real Time"), the model Wyman and Ramsey (2008, §4) use for their coloured and
// textured lights, where Sun et al.'s airlight (airlight.h) serves white point lights.
//
// Over an interval [t0, t1] of a view ray in a homogeneous medium, the light reaching the medium
// is held constant: irradiance E arriving along one direction, so the phase value p(θ) is one
// number too. Single scattering then has the closed form
//
//   L(t0, t1) = E ⊙ σ_s p(θ) ⊙ ∫_{t0}^{t1} e^{-σ_t t} dt = E ⊙ σ_s p(θ) ⊙ (e^{-σ_t t0} - e^{-σ_t t1}) / σ_t,
//
// per channel. Two things the airlight cannot do follow: σ_s and σ_t are RGB (a coloured
// medium is one evaluation, not one per channel), and p is any phase function (H&P's Rayleigh and
// Mie lobes; here whatever the scene's medium has, phase.h, so the picture stays the path
// tracer's). For the sun, H&P's case, E and θ are exact constants. For a spot, the pass
// (textured_spot.h) reads E = I(ω) e^{-σ_t d} / d² and θ at each step's midpoint. The error is
// then their variation across the step: 1/d² varies most, next to the light, where the airlight
// integrates it exactly (but only for an isotropic phase, one channel at a time).
//
// Numerics: the integral is evaluated as e^{-σ_t t0} (-expm1(-σ_t Δ)) / σ_t, without the
// cancellation of the difference in thin media; σ_t = 0 gives Δ exactly. Never negative or NaN
// for finite non-negative inputs. Thread safety: pure functions.
#pragma once

#include "core/rgb.h"
#include "media/phase.h"

namespace caligo {

// One homogeneous medium as the scattering passes see it: coefficients in 1/m.
struct ScatteringMedium {
  RGB sigma_s{0.0f};
  RGB sigma_t{0.0f};
  PhaseFunction phase = IsotropicPhase{};

  bool grey() const;       // the same coefficients in every channel
  bool isotropic() const;  // p = 1/(4π) (an isotropic phase, or a lobe of g = 0)
};

// ∫_{t0}^{t1} e^{-σ t} dt for each channel (0 when t1 <= t0).
RGB extinction_integral(RGB sigma_t, float t0, float t1);

// The transmittance e^{-σ_t t0} at an interval's start is `start`, and `step` = t1 - t0: a march
// that walks consecutive intervals carries `start` along (HoffmanPreethamMarch below).
struct HoffmanPreethamStep {
  RGB integral;  // ∫ e^{-σ_t t} dt over the interval
  RGB end;       // e^{-σ_t t1}
};
HoffmanPreethamStep hoffman_preetham_step(RGB sigma_t, RGB start, float step);

// L(t0, t1) above: `irradiance` in W/m² at the interval, `phase_value` p(θ) in 1/sr.
RGB hoffman_preetham_interval(const ScatteringMedium& medium, RGB irradiance, float phase_value, float t0, float t1);

}  // namespace caligo
