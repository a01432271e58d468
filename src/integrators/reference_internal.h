// Internal to the reference ladder's files (reference_*.cpp, public interface reference.h):
// the helpers more than one rung uses, defined in reference_common.cpp. Helpers of a single
// rung stay in that rung's file.
#pragma once

#include <optional>
#include <vector>

#include "core/ray.h"
#include "core/rgb.h"
#include "core/rng.h"
#include "lights/light_sample.h"
#include "media/medium_stack.h"
#include "scene/scene.h"

namespace caligo::reference_detail {

Vec2 next_2d(Pcg32& rng);

// A stretch [t0, t1) of a ray in one medium of the stack (a scene medium slot, -1: vacuum).
struct MediumRun {
  float t0, t1;
  int medium;
};

enum class Blocking {
  kNone,    // no surface blocks (the stretch of a path the caller knows to be clear)
  kShadow,  // a shadow ray's: Off non-null surfaces block, priority dielectrics block unless the
            // scene's render.priority_shadows, null surfaces never do
};

// The stretches of `ray` within [ray.tmin, ray.tmax) starting in the media of `stack`, or
// nullopt when a surface blocks it. Each crossing of a priority surface updates the stack (no
// Fresnel, no refraction); each stretch lies in the medium the rules give it.
// A shadow ray passes partly transparent surfaces: *through (when given; otherwise they block)
// is multiplied by 1 - opacity for each.
std::optional<std::vector<MediumRun>> medium_runs(const Scene& scene, const Ray& ray, MediumStack stack,
                                                  Blocking blocking, float* through = nullptr);

// A shadow ray's stretches (Blocking::kShadow). A light that casts no shadows sees the
// origin's medium along the whole ray, as in production.
std::optional<std::vector<MediumRun>> shadow_runs(const Scene& scene, const Ray& ray, bool casts_shadows,
                                                  const MediumStack& stack, float* through = nullptr);

// The shadow ray from `origin` (possibly offset off the surface the sample was taken at,
// `sampled_from`) to a light sample: unit direction, aimed at the sampled point and stopping
// short of it. The distance is measured from the origin: the sample's own distance, taken from
// `sampled_from`, would let a ray from an offset origin reach the light's surface.
Ray shadow_ray(Vec3 origin, Vec3 sampled_from, const LightSample& ls);

// One majorant interval of a primitive along a ray, [t0, t1) (half-open, so a point on the
// boundary of a grid primitive's touching intervals is shaded once).
struct Stretch {
  float t0, t1;
  const VolumePrimitive* primitive;
};

// A stretch of the ray with one majorant (the sum over the intervals covering it).
struct MajorantPiece {
  float t0, t1;
  float majorant;
};

// The ladder's own per-thread volume state: one context for interval queries and grid lookups.
VolumeContext& context();

// The media along one ray within [ray.tmin, t_max]: every primitive's majorant intervals
// (and, for `medium` >= 0, the stack medium the ray is in, over the whole stretch), their hull
// [t_lo, t_hi], and (for tracking in one channel) the piecewise-constant majorant
// over the hull, from the intervals' own bounds (so a grid's empty blocks are skipped and its
// dense ones get a tight bound).
struct Segment {
  Ray ray;
  std::vector<Stretch> stretches;
  std::vector<MajorantPiece> pieces;  // ordered along the ray, disjoint
  float t_lo = kInfinity, t_hi = -kInfinity;

  bool empty() const { return stretches.empty(); }
  bool contains(const Stretch& s, float t) const { return t >= s.t0 && t < s.t1; }
};

Segment make_segment(const Scene& scene, const Ray& ray, float t_max, int channel = 0, int medium = -1);

// Sum over the primitives at x(t) of sigma_s,i phase_i(wo, wi): the scattering coefficient
// times the exact per-channel phase mixture.
RGB scattering_times_phase(const Segment& seg, float t, Vec3 wo, Vec3 wi);

// Optical depth along `ray` over [ray.tmin, t_max] of the volume primitives and the stack
// medium `medium` (-1: none), by the midpoint rule on each majorant interval (primitives add,
// so this equals integrating their sum; per-interval stretches keep a homogeneous primitive
// exact instead of blurring its boundary across a step). An unbounded medium over an unbounded
// ray has infinite depth in every channel where it extinguishes.
RGB optical_depth(const Scene& scene, const Ray& ray, float t_max, int steps, int medium);

// exp(-optical depth) over the stretches of `ray`, each in its own stack medium.
RGB transmittance_of_runs(const Scene& scene, const Ray& ray, const std::vector<MediumRun>& runs, int steps);

}  // namespace caligo::reference_detail
