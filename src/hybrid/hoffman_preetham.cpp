#include "hybrid/hoffman_preetham.h"

#include <algorithm>
#include <cmath>
#include <variant>

namespace caligo {
namespace {

struct IsotropicCheck {
  bool operator()(const IsotropicPhase&) const { return true; }
  bool operator()(const HenyeyGreensteinPhase& p) const { return p.g == 0.0f; }
  bool operator()(const SchlickPhase& p) const { return p.k == 0.0f; }
  bool operator()(const DoubleHenyeyGreensteinPhase& p) const { return p.g1 == 0.0f && p.g2 == 0.0f; }
};

// (1 - e^{-σ Δ}) / σ, the integral over an interval starting at transmittance 1.
float unit_integral(float sigma, float step) {
  if (!(sigma > 0.0f)) return step;
  return float(-std::expm1(-double(sigma) * double(step)) / double(sigma));
}

}  // namespace

bool ScatteringMedium::grey() const {
  return sigma_s.r == sigma_s.g && sigma_s.g == sigma_s.b && sigma_t.r == sigma_t.g && sigma_t.g == sigma_t.b;
}

bool ScatteringMedium::isotropic() const { return std::visit(IsotropicCheck{}, phase); }

HoffmanPreethamStep hoffman_preetham_step(RGB sigma_t, RGB start, float step) {
  if (!(step > 0.0f)) return {RGB(0.0f), start};
  if (sigma_t.r == sigma_t.g && sigma_t.g == sigma_t.b) {  // grey: one exp, not three
    const float sigma = std::max(sigma_t.r, 0.0f);
    return {start * unit_integral(sigma, step), start * std::exp(-sigma * step)};
  }
  float integral[3], end[3];
  for (int c = 0; c < 3; ++c) {
    const float sigma = std::max(sigma_t[c], 0.0f);
    integral[c] = start[c] * unit_integral(sigma, step);
    end[c] = start[c] * std::exp(-sigma * step);
  }
  return {RGB(integral[0], integral[1], integral[2]), RGB(end[0], end[1], end[2])};
}

RGB extinction_integral(RGB sigma_t, float t0, float t1) {
  if (!(t1 > t0)) return RGB(0.0f);
  const auto start = [&](int c) { return std::exp(-std::max(sigma_t[c], 0.0f) * t0); };
  return hoffman_preetham_step(sigma_t, RGB(start(0), start(1), start(2)), t1 - t0).integral;
}

RGB hoffman_preetham_interval(const ScatteringMedium& medium, RGB irradiance, float phase_value, float t0, float t1) {
  return irradiance * medium.sigma_s * extinction_integral(medium.sigma_t, t0, t1) * std::max(phase_value, 0.0f);
}

}  // namespace caligo
