// Surface materials: a closed set of simple BSDFs as a std::variant, and what a surface says
// about the space it encloses (nested dielectrics, media/medium_stack.h): an interior medium,
// its IOR and a priority. Those live in Material, not in the BSDF alternatives.
//
// To add a BSDF: define its struct, add it to `Bsdf`, and overload the functions in bsdf.h.
#pragma once

#include <memory>
#include <string>
#include <variant>

#include "core/rgb.h"
#include "materials/opacity_map.h"

namespace caligo {

// Lambertian reflection.
struct DiffuseBsdf {
  RGB reflectance{0.8f};
};

// A smooth interface: Fresnel-weighted specular reflection and refraction. `ior` is the
// ratio n_inside / n_outside across it (inside: the side the normal points away from). In a
// Material it is the IOR relative to vacuum (Material::ior); the path tracer replaces it by
// the ratio of the two media actually on either side of each hit.
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
  // Nested dielectrics. priority 0 (Off): the surface is always seen and never enters the
  // medium stack (the classic behaviour; a dielectric then refracts against the medium the
  // ray is in). Otherwise (smaller is higher; only dielectric and null materials) the surface
  // bounds `interior` (an index into the scene's media, -1: vacuum) of IOR `ior`.
  int priority = 0;
  int interior = -1;
  float ior = 1.0f;  // relative to vacuum; a dielectric's equals its DielectricBsdf::ior
  // Partly transparent surfaces (materials/opacity_map.h): opacity times the map's value at the
  // hit's texture coordinates. Only for non-emitting surfaces of priority off.
  float opacity = 1.0f;
  std::shared_ptr<const OpacityMap> opacity_map;
};

// The surface is a layer the path tracer's march records (its opacity may be below 1).
inline bool partly_transparent(const Material& m) { return m.opacity < 1.0f || m.opacity_map != nullptr; }

}  // namespace caligo
