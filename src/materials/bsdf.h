// Evaluating and sampling the BSDFs of material.h.
//
// Directions are unit vectors in world space pointing away from the surface (wo towards
// the viewer, wi towards the light). `n` is the unit surface normal: the geometric normal
// for the front/back decision, outward for dielectrics (the IOR is on its negative side).
// eval() returns f (no cosine); weight = f |cos| / pdf.
#pragma once

#include <optional>

#include "core/vec.h"
#include "materials/material.h"

namespace caligo {

struct BsdfSample {
  Vec3 wi;
  RGB weight;        // f * |cos theta_i| / pdf
  float pdf = 0.0f;  // solid angle; meaningless for specular samples
  bool specular = false;
};

RGB bsdf_eval(const Bsdf& bsdf, Vec3 n, Vec3 wo, Vec3 wi);
float bsdf_pdf(const Bsdf& bsdf, Vec3 n, Vec3 wo, Vec3 wi);
std::optional<BsdfSample> bsdf_sample(const Bsdf& bsdf, Vec3 n, Vec3 wo, float u_lobe, Vec2 u);

// True when the BSDF is a Dirac delta (next-event estimation is pointless).
bool is_specular(const Bsdf& bsdf);
// The reflectance the albedo AOV shows.
RGB bsdf_albedo(const Bsdf& bsdf);

// Unpolarised Fresnel reflectance of a smooth dielectric interface. cos_i is the cosine on
// the incident side (may be negative: then the ray is inside), eta = n_inside / n_outside.
float fresnel_dielectric(float cos_i, float eta);

}  // namespace caligo
