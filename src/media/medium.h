// What a point in a medium is made of. Coefficients are per metre, linear RGB.
// A volume shader returns these; overlapping volume primitives add their coefficients
// (and mix their phase functions in proportion to sigma_s).
#pragma once

#include "core/rgb.h"
#include "media/phase.h"

namespace caligo {

struct MediumSample {
  RGB sigma_a;   // absorption, 1/m
  RGB sigma_s;   // scattering, 1/m
  RGB emission;  // emitted radiance per metre of path, W m^-3 sr^-1
  PhaseFunction phase;
  // Holdout extinction sigma_h, 1/m (grey): it attenuates like absorption, and what it removes
  // from a camera ray is background the compositor's plate shows (the seed's holdouts).
  float holdout = 0.0f;

  RGB sigma_t() const { return sigma_a + sigma_s + RGB(holdout); }
};

}  // namespace caligo
