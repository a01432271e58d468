// How much of a light's emission reaches a point: surfaces block (null surfaces do not),
// volume primitives attenuate, and in scenes with priority surfaces the media the medium stack
// puts each stretch of the shadow ray in attenuate too. Shared by surface and volume
// next-event estimation.
#pragma once

#include "core/rgb.h"
#include "integrators/path_tracer.h"
#include "lights/light_sample.h"

namespace caligo {

// Transmittance from `origin` (offset off its surface by the caller) to the light sample
// `ls` taken there: 0 when a surface blocks it (unless the light casts no shadows), the
// volumes' transmittance otherwise.
//
// Nested media (Scene::has_priority_objects()): the shadow ray starts with the path's stack
// (scratch.stack, plus the queued false crossings of the current segment before `segment_t`,
// the origin's distance along it). Hits on priority surfaces that do not block
// (Scene::shadow_deferred()) come back unsorted from the occlusion query; only when nothing
// else blocks are they sorted and walked with a copy of the stack, each stretch attenuated by
// the medium the rules give it (no Fresnel: approximate caustics). A ray that meets no
// priority surface costs one occlusion query and one march, as without nesting. A light that
// casts no shadows sees the origin's medium along the whole ray.
//
// *through_interface (when given) is set when the ray crossed a priority dielectric for real
// (render.priority_shadows): no BSDF or phase sample can reach the light along that straight
// line (it would refract), so the caller weights such a sample 1, not by MIS.
RGB light_transmittance(const Scene& scene, Vec3 origin, Vec3 sampled_from, const LightSample& ls,
                        bool casts_shadows, float jitter, PathScratch& scratch, PathCounters& counters,
                        float segment_t = kInfinity, bool* through_interface = nullptr);

}  // namespace caligo
