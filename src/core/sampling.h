// Sampling triads: for every warp of the unit square Caligo uses,
//   sample_X(u, ...)  maps canonical samples to the domain,
//   X_pdf(...)        gives the density of that map (w.r.t. the measure named in its comment),
//   invert_X(x, ...)  maps a domain point back to the u that produces it.
// Each triad has a normalisation test, a chi-squared test and a round-trip test in
// sampling_test.cpp.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/vec.h"

namespace caligo {

// Concentric map of the unit square onto the unit disk (Shirley & Chiu 1997). Area measure.
Vec2 sample_uniform_disk_concentric(Vec2 u);
float uniform_disk_pdf();
Vec2 invert_uniform_disk_concentric(Vec2 p);

// Uniform directions on the unit sphere. Solid-angle measure.
Vec3 sample_uniform_sphere(Vec2 u);
float uniform_sphere_pdf();
Vec2 invert_uniform_sphere(Vec3 w);

// Uniform directions on the +Z hemisphere. Solid-angle measure.
Vec3 sample_uniform_hemisphere(Vec2 u);
float uniform_hemisphere_pdf();
Vec2 invert_uniform_hemisphere(Vec3 w);

// Cosine-weighted directions on the +Z hemisphere (Malley's method). Solid-angle measure.
Vec3 sample_cosine_hemisphere(Vec2 u);
float cosine_hemisphere_pdf(float cos_theta);
Vec2 invert_cosine_hemisphere(Vec3 w);

// Uniform directions in the cone around +Z with cos(theta) >= cos_theta_max. Solid angle.
Vec3 sample_uniform_cone(Vec2 u, float cos_theta_max);
float uniform_cone_pdf(float cos_theta_max);
Vec2 invert_uniform_cone(Vec3 w, float cos_theta_max);

// Uniform points on a triangle, returned as barycentrics (b0, b1, b2) with b0+b1+b2 = 1.
// Area measure: pdf = 1 / area (the triangle's area is the caller's).
Vec3 sample_uniform_triangle(Vec2 u);
Vec2 invert_uniform_triangle(Vec3 barycentrics);

// Piecewise-constant discrete distribution over non-negative weights (e.g. light power).
class DiscreteDistribution {
 public:
  DiscreteDistribution() = default;
  explicit DiscreteDistribution(std::span<const float> weights);

  bool empty() const { return pmf_.empty(); }
  size_t size() const { return pmf_.size(); }
  float total() const { return total_; }
  // Picks an index with probability pmf(i); *u_remapped (optional) is u rescaled to [0, 1)
  // inside the chosen bucket, so one sample can be reused.
  int sample(float u, float* pmf_out = nullptr, float* u_remapped = nullptr) const;
  float pmf(int index) const { return pmf_[size_t(index)]; }
  // The smallest u that selects `index` (the start of its bucket).
  float invert(int index) const { return cdf_[size_t(index)]; }

 private:
  std::vector<float> pmf_;
  std::vector<float> cdf_;  // size() + 1 entries, cdf_[0] = 0, cdf_.back() = 1
  float total_ = 0.0f;
};

// Multiple importance sampling weights (Veach 1997), for one sample from each of two strategies.
float power_heuristic(int nf, float f_pdf, int ng, float g_pdf);
float balance_heuristic(int nf, float f_pdf, int ng, float g_pdf);

}  // namespace caligo
