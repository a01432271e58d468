// Surface materials: a closed set of simple BSDFs as a std::variant.
//
// Later stages give a material an interior medium and a priority (nested dielectrics);
// those fields live in Material, not in the BSDF alternatives.
//
// To add a BSDF: define its struct, add it to `Bsdf`, and overload the functions in bsdf.h.
#pragma once

#include <string>
#include <variant>

#include "core/rgb.h"

namespace caligo {

// Lambertian reflection.
struct DiffuseBsdf {
  RGB reflectance{0.8f};
};

// A smooth interface between the outside (IOR 1) and a dielectric of the given IOR:
// Fresnel-weighted specular reflection and refraction.
struct DielectricBsdf {
  float ior = 1.5f;
};

// Emits and does not scatter (black body of an area light).
struct BlackBsdf {};

// Rays pass straight through as if the surface were not there. Used for invisible
// boundaries (of media, in later stages).
struct NullBsdf {};

using Bsdf = std::variant<DiffuseBsdf, DielectricBsdf, BlackBsdf, NullBsdf>;

struct Material {
  std::string name;
  Bsdf bsdf;
  RGB emission;  // radiance leaving the front face, W m^-2 sr^-1; black for non-emitters
  bool two_sided_emission = false;
};

}  // namespace caligo
