// How much of a light's emission reaches a point: surfaces block (null surfaces do not),
// volume primitives attenuate. Shared by surface and volume next-event estimation.
#pragma once

#include "core/rgb.h"
#include "integrators/path_tracer.h"
#include "lights/light_sample.h"

namespace caligo {

// Transmittance from `origin` (offset off its surface by the caller) to the light sample
// `ls` taken there: 0 when a surface blocks it (unless the light casts no shadows), the
// volumes' transmittance otherwise.
RGB light_transmittance(const Scene& scene, Vec3 origin, Vec3 sampled_from, const LightSample& ls,
                        bool casts_shadows, float jitter, PathScratch& scratch, PathCounters& counters);

}  // namespace caligo
