// Reproducible sample values: every value is a pure function of
// (seed, pixel, sample index, dimension), so an image does not depend on the thread
// count or the order in which tiles run.
//
// Values come from a 2D Sobol' sequence (the first two Sobol' dimensions: van der Corput
// and its (0,2)-partner), made independent across pixels and dimensions by hash-based
// Owen scrambling and a per-(pixel, dimension) shuffle of the sample index (Burley 2020,
// "Practical Hash-based Owen Scrambling"). Each 1D or 2D request is stratified over the
// sample indices of its pixel; different dimensions are decorrelated by their hashes.
//
// Dimensions are named (namespace sample_dim) so two uses never collide silently.
#pragma once

#include <cstdint>

#include "core/vec.h"

namespace caligo {

// Named sample dimensions. A path vertex at depth d uses
// kBounceBase + d * kPerBounce + <offset>; camera dimensions come first.
namespace sample_dim {
inline constexpr uint32_t kFilm = 0;  // 2D: position inside the pixel
inline constexpr uint32_t kLens = 1;  // 2D: the thin lens's aperture (Camera::has_aperture)
inline constexpr uint32_t kBounceBase = 2;
enum Bounce : uint32_t {
  kLightSelect = 0,      // 1D: which light for next-event estimation
  kLightPosition,        // 2D: point / direction on that light
  kBsdfLobe,             // 1D: reflect or refract, lobe choice
  kBsdfDirection,        // 2D: scattered direction
  kRussianRoulette,      // 1D: path termination
  kMarchJitter,          // 1D: where heterogeneous steps are shaded
  kVolumeLightSelect,    // 1D: light for next-event estimation from the medium
  kDistanceSample,       // 2D: x picks equiangular or density sampling, y the distance
  kDensityChannel,       // 1D: colour channel of density (sigma_s T) sampling
  kVolumeLightPosition,  // 2D: light sample at the chosen distance
  kFreeFlightChannel,    // 1D: colour channel of free-flight sampling
  kFreeFlightDistance,   // 1D: collision distance
  kPhaseLobe,            // 1D: lobe of a mixed phase function
  kPhaseDirection,       // 2D: scattered direction
  kVolumeNeeRoulette,    // 1D: whether a thinly scattering segment gets next-event estimation
  kPerBounce
};
constexpr uint32_t bounce(int depth, Bounce which) {
  return kBounceBase + uint32_t(depth) * kPerBounce + which;
}
// Volume emission as a light (integrators/emission_direct.h) has a space of its own above the
// per-bounce dimensions, so adding it left every other dimension, and image, as it was.
inline constexpr uint32_t kEmissionBase = 1u << 30;
enum Emission : uint32_t {
  kEmissionBlock = 0,  // 1D: which emissive block
  kEmissionPointXY,    // 2D: the point inside it
  kEmissionPointZ,     // 1D
  kEmissionJitter,     // 1D: the march along the chosen direction
  kPerEmission
};
constexpr uint32_t emission(int vertex, Emission which) {
  return kEmissionBase + uint32_t(vertex) * kPerEmission + which;
}
// Path guiding's choices (integrators/guided_direction.h), likewise apart: unguided renders keep
// every other dimension.
inline constexpr uint32_t kGuidingBase = 3u << 29;
enum Guiding : uint32_t {
  kGuideChoice = 0,  // 1D: the guided density or the BSDF / phase function
  kGuideDirection,   // 2D: the guided direction
  kPerGuiding
};
constexpr uint32_t guiding(int vertex, Guiding which) { return kGuidingBase + uint32_t(vertex) * kPerGuiding + which; }
}  // namespace sample_dim

class Sampler {
 public:
  Sampler(uint64_t seed, Vec2i pixel, uint32_t sample_index);

  float get_1d(uint32_t dimension) const;  // in [0, 1)
  Vec2 get_2d(uint32_t dimension) const;   // in [0, 1)^2
  // A 64-bit key unique to (seed, pixel, sample index, dimension), to seed a Pcg32 for estimators
  // that draw an unbounded number of values (tracking): still a pure function of the sample.
  uint64_t stream_key(uint32_t dimension) const;

  uint32_t sample_index() const { return index_; }
  Vec2i pixel() const { return pixel_; }

 private:
  uint64_t pixel_key_;  // hash of (seed, pixel): computed once, mixed with each dimension
  Vec2i pixel_;
  uint32_t index_;
};

// The building blocks, exposed for tests and benchmarks.
uint32_t sobol_dim0(uint32_t index);                          // van der Corput (bit reversal)
uint32_t sobol_dim1(uint32_t index);                          // second Sobol' dimension
uint32_t nested_uniform_scramble(uint32_t x, uint32_t seed);  // Owen scrambling of a 32-bit fraction

}  // namespace caligo
