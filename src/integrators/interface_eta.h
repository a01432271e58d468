// The IOR ratio at a dielectric hit with nested media (media/medium_stack.h).
#pragma once

#include <optional>

#include "media/medium_stack.h"

namespace caligo {

// n_inside / n_outside for DielectricBsdf (inside: the side the geometric normal points away
// from; front_face: the ray arrives on the side it points to). A priority surface's two sides
// hold the media the stack rules give before and after its crossing, so a liquid modelled
// slightly overlapping its glass refracts glass -> liquid. An Off surface (no entry) encloses
// its own material IOR against the medium the ray is in.
inline float interface_eta(const MediumStack& stack, const std::optional<MediumEntry>& entry, float material_ior,
                           bool front_face) {
  if (!entry) return material_ior / stack.current().ior;
  const MediumStack::Crossing c = stack.peek(*entry);
  return front_face ? c.after.ior / c.before.ior : c.before.ior / c.after.ior;
}

}  // namespace caligo
