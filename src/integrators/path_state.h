// The state a camera path carries from one event to the next (path_tracer.cpp): throughput,
// what the last scattering event sampled (for the MIS weight of a light the next ray hits), the
// bounce counts PathLimits bounds, and the light-layer and alpha bookkeeping.
#pragma once

#include "core/ray.h"
#include "core/rgb.h"
#include "integrators/path_sample.h"

namespace caligo {

// The state carried from one scattering event to the next.
struct PathState {
  RGB throughput{1.0f};
  // Hero-channel spectral MIS of chromatic marched segments (path_tracer.cpp, chromatic_fate):
  // the channel whose fates the path samples (-1 until its first chromatic segment) and the
  // path's pdf of those fates in each channel, normalised to average 1.
  int hero_channel = -1;
  RGB channel_pdf{1.0f};
  bool specular_bounce = true;  // the camera ray counts as specular: no MIS on what it sees
  // Only specular events so far (the camera ray, mirrors, glass): what a ray sees now is what
  // the camera sees, so an environment with visible = false shows black to it.
  bool camera_view = true;
  float scatter_pdf = 0.0f;     // solid-angle pdf of the direction that produced the current ray
  // The MIS weight of the volume emission the current ray gathers against sampling it as a
  // light at the ray's origin (integrators/emission_direct.h); 1 when nothing samples it.
  float emission_weight = 1.0f;
  Vec3 scatter_origin;          // where that direction was sampled
  // The light choice next-event estimation made at that vertex, whose pmf the MIS weight of a
  // light hit needs (LightSampler::choice_pmf: the light's probability of being among the
  // choices): at a surface, choice_pmf(scatter_origin, scatter_normal); after a marched
  // scattering event, choice_pmf_segment(scatter_segment), the segment volume NEE chose its lights
  // for; after a tracked one, choice_pmf(scatter_origin) (light_choice_at_point).
  bool deferred_nee = false;  // PathSettings::deferred_nee > 0
  Vec3 scatter_normal;
  bool scattered_in_medium = false;
  // A tracked scattering event chose its light by the sampler's point form at scatter_origin; a
  // marched one by its segment's form (scatter_segment).
  bool light_choice_at_point = false;
  Ray scatter_segment;
  int events = 0;               // scattering events so far (surface and volume, every one)
  int surface_bounces = 0;
  int volume_bounces = 0;
  // A run of consecutive scattering events in media counts as ONE bounce against max_bounces
  // (max_volume_bounces bounds the events inside runs): so max_bounces 1 is direct light only,
  // surfaces or media, and a long chain of scattering in fog costs a path one surface bounce.
  int volume_runs = 0;
  bool in_volume_run = false;
  // Real crossings of medium boundaries (priority null surfaces): not events, but each starts a
  // new segment whose free-flight and NEE samples must not reuse the previous segment's.
  int boundary_crossings = 0;
  // Light-layer bookkeeping (integrators/path_sample.h): non-specular events so far and where
  // the first of them happened.
  int nonspecular_events = 0;
  bool first_event_in_medium = false;
  // Alpha: what of the background the camera sees through this path, so far (1 - alpha).
  float visibility = 0.0f;
  bool first_hit_recorded = false;

  // The sampler's vertex index: events plus boundary crossings (= events without nested media).
  int vertex() const { return events + boundary_crossings; }

  // Whether the path may have another bounce of PathLimits::max_bounces (a surface bounce or the
  // start of a volume run).
  bool may_bounce(int max_bounces) const { return surface_bounces + volume_runs < max_bounces; }

  // The layer of light that reaches the camera along the path as it is: emission and light hits
  // (`seen` is the layer when the camera sees it directly).
  LightKind arriving(LightKind seen) const {
    if (nonspecular_events == 0) return seen;
    const bool direct = nonspecular_events == 1;
    if (first_event_in_medium) return direct ? LightKind::kVolumeDirect : LightKind::kVolumeIndirect;
    return direct ? LightKind::kSurfaceDirect : LightKind::kSurfaceIndirect;
  }
  // The layer of a light connection made at a new non-specular event (in a medium or not).
  LightKind connected(bool in_medium) const {
    const bool medium_first = nonspecular_events == 0 ? in_medium : first_event_in_medium;
    const bool direct = nonspecular_events == 0;
    if (medium_first) return direct ? LightKind::kVolumeDirect : LightKind::kVolumeIndirect;
    return direct ? LightKind::kSurfaceDirect : LightKind::kSurfaceIndirect;
  }
  void count_nonspecular_event(bool in_medium) {
    if (nonspecular_events == 0) first_event_in_medium = in_medium;
    ++nonspecular_events;
  }
};

}  // namespace caligo
