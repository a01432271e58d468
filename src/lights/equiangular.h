// Equiangular sampling (Kulla & Fajardo 2012, "Importance Sampling Techniques for Path
// Tracing in Participating Media"): distances t in [a, b] along a ray, with density
// proportional to 1 / (D^2 + (t - delta)^2), which cancels the inverse-square falloff of a
// point light at perpendicular distance D from the ray whose foot point is at t = delta.
//
// The pdf is a Cauchy density: pdf(t) = D / ((theta_b - theta_a) (D^2 + (t - delta)^2)) with
// theta_x = atan((x - delta) / D). For D = 0 (the light lies on the ray's line: the
// "flashlight" case of the seed) the density is proportional to 1/(t - delta)^2 and has the
// closed form used in equiangular.cpp; it needs delta outside [a, b].
#pragma once

#include "core/vec.h"

namespace caligo {

// The ray segment [a, b] (a < b) and the light's position relative to the ray.
struct EquiangularSetup {
  float a, b;
  float delta;  // ray parameter of the point closest to the light: dot(light - origin, dir) for a unit dir
  float D;      // distance from the light to the ray's line, >= 0
};

// The setup for the segment [a, b] of a ray with unit direction towards a light position.
EquiangularSetup make_equiangular_setup(Vec3 origin, Vec3 unit_dir, Vec3 light, float a, float b);

// The distribution of one setup with its angles computed once (an atan2 and an atan): a light
// connection samples a distance and then evaluates the pdf at it.
class EquiangularDistribution {
 public:
  explicit EquiangularDistribution(const EquiangularSetup& s);
  float sample(float u) const;
  float pdf(float t) const;
  float invert(float t) const;  // the CDF at t

 private:
  int regime_;
  double a_, b_, delta_, D_;
  double xa_;       // a - delta
  double span_;     // Cauchy: theta_b - theta_a; inverse square: 1/x_a - 1/x_b; uniform: b - a
  double theta_a_;  // Cauchy: atan(x_a / D)
};


}  // namespace caligo
