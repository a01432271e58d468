// How the volumetric path tracer traces a path: its limits and the choices of its estimators,
// as plain data below every pipeline (settings/: what a scene file and a command line set).
// One value of these is embedded in RenderSettings (settings/render_settings.h) and passed to
// trace_path unchanged; a scene file's "render" object sets its limits and priority_shadows.
// PathLimits alone is also what the reference ladder obeys (ReferenceOptions,
// integrators/reference.h), so every pipeline counts a path's events the same way.
#pragma once

#include "core/enum_names.h"
#include "settings/light_sampler_kind.h"

namespace caligo {

// How long a path may be. Two counts, both checked before an event happens:
//   - max_bounces: each surface bounce counts one, and so does each RUN of consecutive
//     scattering events in media (a path that scatters ten times in fog without meeting a
//     surface has used one). So 0 is emission and background seen directly, 1 is direct
//     lighting only (of surfaces and of media), 2 adds one indirect bounce. A path that has
//     used them up may not start another run in a medium either. Scene key "max_bounces"
//     (alias "max_depth"), CLI --max-bounces (alias --max-depth).
//   - max_volume_bounces: every scattering event in media counts one, inside runs too; it
//     bounds the length of the runs (scene key "max_volume_bounces", CLI --max-volume-bounces).
//     1024 by default, the seed's "thousand and more": walks in dense bright media take
//     hundreds of events (docs/techniques.md); paths that end sooner cost nothing more.
// Null-surface and medium-boundary crossings count against neither.
struct PathLimits {
  int max_bounces = 8;
  int max_volume_bounces = 1024;
};

// How next-event estimation in media picks the distance along a ray segment.
enum class DistanceSampling {
  kDensity,      // pdf proportional to sigma_s T
  kEquiangular,  // pdf cancelling the light's inverse-square falloff (density for lights at infinity)
  kMis,          // one of the two at random, weighted by the balance heuristic (one-sample MIS);
                 // equiangular's share follows the segment's optical depth (volume_direct.h)
  kMisFixed,     // the same with equiangular's share fixed at 3/4 (the former default)
};

// How segments after the camera segment (bounce rays from a scattering or surface event) and the
// shadow rays of those events estimate their volumes (docs/techniques.md, "Tracking after the
// first bounce"). The camera segment, and the shadow rays of its light connections and of the
// first surface it meets, are always marched.
enum class SecondarySegments {
  kMarch,  // decoupled marching, as the camera segment (the former behaviour)
  kTrack,  // spectral tracking for free flight, ratio tracking for shadow rays, every medium
  kAuto,   // tracking where a segment crosses a heterogeneous span (grids, noise, falloff) of
           // media that do not emit; homogeneous segments keep their closed forms and
           // equiangular sampling, emissive ones their exact per-step emission
};

// Where path guiding (guiding/guiding_field.h) samples scattering directions: at diffuse surfaces,
// at scattering events in media, both, or nowhere. Guided vertices mix the learnt density with
// the BSDF's or phase function's by one-sample MIS (integrators/guided_direction.h).
enum class GuidingMode { kOff, kSurface, kVolume, kAll };

// --distance-sampling, --secondary and --guiding.
inline constexpr std::array<EnumName<DistanceSampling>, 4> kDistanceSamplingNames{
    {{DistanceSampling::kMis, "mis"},
     {DistanceSampling::kMisFixed, "mis-fixed"},
     {DistanceSampling::kDensity, "density"},
     {DistanceSampling::kEquiangular, "equiangular"}}};
inline constexpr std::array<EnumName<GuidingMode>, 4> kGuidingModeNames{{{GuidingMode::kOff, "off"},
                                                                          {GuidingMode::kSurface, "surface"},
                                                                          {GuidingMode::kVolume, "volume"},
                                                                          {GuidingMode::kAll, "all"}}};
inline constexpr std::array<EnumName<SecondarySegments>, 3> kSecondarySegmentsNames{
    {{SecondarySegments::kAuto, "auto"}, {SecondarySegments::kTrack, "track"}, {SecondarySegments::kMarch, "march"}}};

struct PathSettings {
  PathLimits limits;
  // Shadow rays pass through dielectrics of priority other than Off, attenuated by the media
  // the priority rules put them in (approximate caustics; lights inside glass or water).
  // Off: those dielectrics block shadow rays like any other. Null medium boundaries never
  // block. Scene key render.priority_shadows.
  bool priority_shadows = false;
  int russian_roulette_depth = 3;  // roulette starts after this many events (surface and volume)
  int max_null_crossings = 256;    // guards against endless chains of null surfaces
  DistanceSampling distance_sampling = DistanceSampling::kMis;
  // Volume next-event estimation along a marched segment runs with probability
  // min(1, scale * P(scatter in segment)), reweighted; tracked segments always connect.
  float volume_nee_scale = 2.0f;
  // How next-event estimation picks a light (lights/light_sampler.h; Scene::light_sampler). The
  // tree is the default: ~90x less MSE than power at equal time on many-lamps, and the same
  // choice (bit for bit) as power in scenes with one light.
  LightSamplerKind light_sampler = LightSamplerKind::kTree;
  // true (absorption by weight): the path scatters with probability S / (S + P), S the
  // segment's scattering weight and P its end transmittance, and otherwise passes with weight
  // T (S + P) / P. false: free-flight sampling in proportion to sigma_t T, weighted by the
  // albedo (the former estimator, kept for comparisons).
  bool absorption_by_weight = true;
  // Deferred next-event estimation (the seed's "optimizations for multiple scattering"): 0 (the
  // default) connects each medium segment to a light as the path goes; K > 0 builds the whole
  // path first, keeping its marched medium segments with their transmittance records (and the
  // scattering vertices of tracked segments), then connects K of them, chosen with probability
  // proportional to throughput x the segment's integral of sigma_s T and weighted by the inverse;
  // a chosen segment connects as per-segment NEE does (equiangular and density sampling along
  // its record). Light hits from medium vertices then count zero (the connections alone are
  // unbiased). Off by default: it lost or tied at equal time wherever measured (docs/techniques.md).
  int deferred_nee = 0;
  SecondarySegments secondary = SecondarySegments::kAuto;
  // Tracked shadow rays by residual ratio tracking with each span's minimum as the control
  // (tracking/tracking.h); false: plain ratio tracking (the former estimator, for benchmarks).
  bool residual_ratio_tracking = true;
  // Emissive grids sampled as lights at every scattering vertex, MIS-weighted with the bounce
  // rays that gather their emission (integrators/emission_direct.h); false: emission is found by
  // bounce rays alone (the former behaviour, for benchmarks).
  bool sample_emission = true;
  // Path guiding (docs/techniques.md, "Path guiding"): the render loop trains a field in
  // iterations of doubling sample counts and the path tracer samples from it where this says.
  // Off with deferred_nee > 0 (a deferred connection has no single incident direction to learn).
  GuidingMode guiding = GuidingMode::kOff;
  // With volume guiding: where a path scatters in a grey marched segment is drawn from a mixture
  // of the record's density and that density times the learnt fluence (integrators/
  // guided_distance.h). Off: on `lamp-in-fog` it left the error per sample unchanged for 18 %
  // more time (docs/benchmarks.md); kept, unexposed, for bench_noise to measure.
  bool guided_distances = false;
};

}  // namespace caligo
