// How much of a light's emission reaches a point: surfaces block (null surfaces do not),
// volume primitives attenuate, and in scenes with priority surfaces the media the medium stack
// puts each stretch of the shadow ray in attenuate too. Shared by surface and volume
// next-event estimation.
#pragma once

#include <cstdint>

#include "core/rgb.h"
#include "integrators/path_context.h"
#include "lights/light_sample.h"

namespace caligo {

// How a shadow ray estimates the transmittance of its volumes: marched with `jitter` (the
// march's step rules), or ratio-tracked (tracking/tracking.h) with a generator seeded by
// `tracking_key`, always (kTrack) or where the ray crosses a heterogeneous span (kAuto).
struct ShadowMedium {
  ShadowMedium(float march_jitter = 0.5f) : jitter(march_jitter) {}  // NOLINT: a plain jitter marches
  float jitter;
  SecondarySegments policy = SecondarySegments::kMarch;
  uint64_t tracking_key = 0;
  bool residual = true;  // residual ratio tracking (PathSettings::residual_ratio_tracking)
  bool priority_shadows = false;  // priority dielectrics pass shadow rays (PathSettings::priority_shadows)
};

// The shadow medium of a light connection made at path vertex `vertex` (its sample dimensions),
// whose event is the camera segment's or its first surface's (`secondary` false: marched) or
// a later one's (PathSettings::secondary).
ShadowMedium shadow_medium(const PathContext& ctx, int vertex, bool secondary, sample_dim::Bounce key_dimension);

// Transmittance from `origin` (offset off its surface by the caller) to the light sample
// `ls` taken there: 0 when a surface blocks it (unless the light casts no shadows), the
// volumes' transmittance otherwise.
//
// Nested media (Scene::has_priority_objects()): the shadow ray starts with the path's stack
// (scratch.stack, plus the queued false crossings of the current segment before `segment_t`,
// the origin's distance along it). Hits on priority surfaces that do not block
// (Scene::shadow_deferred(priority_shadows)) come back unsorted from the occlusion query; only when nothing
// else blocks are they sorted and walked with a copy of the stack, each stretch attenuated by
// the medium the rules give it (no Fresnel: approximate caustics). A ray that meets no
// priority surface costs one occlusion query and one march, as without nesting. A light that
// casts no shadows sees the origin's medium along the whole ray.
//
// *through_interface (when given) is set when the ray crossed a priority dielectric for real
// (PathSettings::priority_shadows): no BSDF or phase sample can reach the light along that straight
// line (it would refract), so the caller weights such a sample 1, not by MIS.
RGB light_transmittance(const Scene& scene, Vec3 origin, Vec3 sampled_from, const LightSample& ls,
                        bool casts_shadows, ShadowMedium medium, PathScratch& scratch, PathCounters& counters,
                        float segment_t = kInfinity, bool* through_interface = nullptr);

}  // namespace caligo
