// Rung 1 of the reference ladder (reference.h): transmittance by the midpoint rule.
#include "integrators/reference.h"

#include "integrators/reference_internal.h"

namespace caligo {

using namespace reference_detail;

RGB reference_transmittance(const Scene& scene, const Ray& ray, float t_max, int steps) {
  return exp_neg(optical_depth(scene, ray, t_max, steps, -1));
}

RGB reference_transmittance(const Scene& scene, const Ray& ray, float t_max, int steps, const MediumStack& stack) {
  Ray clipped = ray;
  clipped.tmax = t_max;
  return transmittance_of_runs(scene, ray, *medium_runs(scene, clipped, stack, Blocking::kNone), steps);
}

}  // namespace caligo
