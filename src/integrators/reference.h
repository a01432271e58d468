// The reference ladder: deliberately simple, slow volume estimators that are easy to check
// by reading, kept so tests can hold the production path tracer (path_tracer.h) against
// them. They share none of its estimators (no march(), no TransmittanceRecord, no
// equiangular or density-proportional distance sampling, no MIS); they share its inputs:
// the scene queries, the volume primitives' majorant intervals and spans (VolumeScene::
// intervals, build_spans) and shaders (shade_volume), and the sampling routines of lights,
// phase functions and BSDFs (sample_light, phase_sample, bsdf_sample).
//
// Rungs, each simpler to trust than the next:
//   1. reference_transmittance: optical depth by the midpoint rule (exact for homogeneous media).
//   2. reference_single_scattering: light scattered once, by uniform distance sampling along
//      the ray and brute-force transmittance on both sides; every light, every call.
//   3. reference_delta_tracking: all orders of scattering by scalar delta tracking in one
//      colour channel, next-event estimation with ratio tracking.
//
// Nested media (media/medium_stack.h, scenes with priority surfaces): every rung starts a
// camera ray in Scene::camera_stack() and walks each ray's surface crossings in order
// (EmbreeScene::all_hits) with its own copy of the stack, applying the MediumStack rules
// itself: priority surfaces whose crossing is false are crossed without interaction, real
// priority null surfaces change the medium and are crossed, a dielectric's crossing joins the
// stack only when the sampled direction transmits. The medium the stack puts a stretch in is
// a homogeneous unbounded primitive (VolumeScene::intervals' `medium`), tracked like any other.
// Shadow rays carry a copy of the stack: Off non-null surfaces block, priority dielectrics
// block unless the scene's PathSettings::priority_shadows, null surfaces never do, and each stretch
// between priority crossings is attenuated by the medium the rules give it (no Fresnel).
//
// Conventions of all three: rays have unit directions (t is in metres); overlapping volume
// primitives add their coefficients, and the phase function at a point is the exact
// per-channel mixture sum_i sigma_s,i phase_i / sigma_s. (Production weights the lobes by
// each primitive's average sigma_s, which agrees with this unless overlapping primitives
// have both different phase functions and differently coloured sigma_s.) Volume emission is
// ignored throughout: the ladder checks scattering, not emission.
#pragma once

#include <cstdint>
#include <vector>

#include "core/ray.h"
#include "core/rgb.h"
#include "core/rng.h"
#include "settings/path_settings.h"
#include "media/medium_stack.h"
#include "scene/scene.h"

namespace caligo {

// exp(-optical depth) along `ray` over [ray.tmin, min(t_max, far end of the volume intervals)].
// Each majorant interval of the ray is integrated separately with `steps` equal midpoint
// steps (primitives add, so this equals integrating their sum; per-interval stretches keep
// a homogeneous primitive exact instead of blurring its boundary across a step).
// Surfaces are ignored: visibility is the caller's business.
RGB reference_transmittance(const Scene& scene, const Ray& ray, float t_max, int steps);
// The same through nested media: the ray starts in the media of `stack`, and each priority
// surface it crosses within [ray.tmin, t_max) updates a copy of it by the rules; each stretch
// between crossings adds the medium the rules give it to the volume primitives. No surface
// blocks (visibility is still the caller's business). A stretch of an unbounded medium that
// runs to infinity has transmittance 0 in every channel the medium extinguishes.
RGB reference_transmittance(const Scene& scene, const Ray& ray, float t_max, int steps, const MediumStack& stack);

// The single-scattered medium radiance arriving at ray.origin along -ray.direction, and
// nothing else: no surface shading, no surface or environment emission seen directly, no
// volume emission. Light from every light reaches the scattering point unscattered (surfaces
// block it, media attenuate it); the path ends at the nearest non-null surface. Averages
// `samples` uniform distance samples over the ray's stretch of the volume intervals; area and
// environment lights get a few light samples each per distance sample, delta lights one.
// Nested media: the ray starts in Scene::camera_stack(); it crosses false hits and real
// priority null boundaries (the medium changes there) and ends at the first other surface it
// sees, a real dielectric crossing included: no refraction, so light seen through glass is not
// single-scattered light of this estimator. Distance samples cover the stack media of each
// stretch too, and shadow rays follow the shadow rules above from the stack at the sample.
// Throws std::invalid_argument when the ray runs to infinity inside a medium (no uniform
// distance pdf exists there).
RGB reference_single_scattering(const Scene& scene, const Ray& ray, int samples, Pcg32& rng);

// Radiance along `ray` with all orders of scattering within `limits`, counted as the production
// integrator counts them (PathLimits, settings/path_settings.h): surface bounces plus runs of
// consecutive volume events up to max_bounces, and volume events up to max_volume_bounces. By
// delta tracking with the piecewise-constant majorant of the volume intervals (a grid's empty
// blocks are skipped, each run of blocks tracked with its own bound).
// One colour channel is traced per call, chosen uniformly: the result holds 3x the estimate
// in that channel and zero in the others, so its expectation is the full RGB radiance and
// chromatic media need no spectral MIS.
// Lights are reached two ways, never both for one path vertex, so nothing counts twice:
//   - after a diffuse surface event or a phase-function event, by next-event estimation only
//     (all lights, one sample each, ratio-tracking transmittance along the shadow rules);
//   - emission on hit (area lights, emissive surfaces, the environment) counts only when the
//     ray that reaches it left the camera or a specular (dielectric) event, which next-event
//     estimation cannot sample. Light through glass onto a diffuse surface (caustics) is
//     therefore found only by paths that hit the light after the glass.
// Diffuse surfaces scatter (NEE plus cosine sampling), null surfaces are crossed, black
// surfaces absorb; dielectrics reflect or refract by bsdf_sample (Fresnel-chosen, weight 1 or
// 1/eta^2) with the IOR ratio of the media on either side as production computes it: for a
// priority surface the stack's media before and after the crossing (MediumStack::peek), for an
// Off one its IOR over the current medium's. Each dielectric event counts as a surface bounce.
// Volume emission is ignored.
RGB reference_delta_tracking(const Scene& scene, const Ray& ray, PathLimits limits, Pcg32& rng);

enum class ReferenceEstimator { kSingleScattering, kDeltaTracking };

struct ReferenceOptions {
  ReferenceEstimator estimator = ReferenceEstimator::kDeltaTracking;
  int samples_per_pixel = 16;  // jittered camera rays per pixel
  // Delta tracking's limits; deeper by default than production's (PathLimits{}), so the
  // reference is cut only where its tests make it so.
  PathLimits limits{.max_bounces = 64, .max_volume_bounces = 64};
  int distance_samples = 1;  // single scattering: distance samples per camera ray
  uint64_t seed = 0;
};

// Per-pixel means of an estimator over the camera's jittered pixel rays, row-major, like the
// colour channels of render()'s image. Deterministic for a given seed (pixels run in parallel,
// each with its own generator).
std::vector<RGB> reference_image(const Scene& scene, Vec2i resolution, const ReferenceOptions& options);

// The mean of reference_image over all pixels.
RGB reference_mean_radiance(const Scene& scene, Vec2i resolution, const ReferenceOptions& options);
RGB reference_mean_radiance(const Scene& scene, Vec2i resolution, int samples_per_pixel,
                            ReferenceEstimator which, uint64_t seed);

}  // namespace caligo
