// The surface path tracer: next-event estimation and BSDF sampling combined by multiple
// importance sampling (power heuristic, Veach 1997), Russian roulette, a maximum depth.
//
// One call traces one camera path. The result is a pure function of the scene, the camera
// ray and the Sampler, so images do not depend on thread count or scheduling.
// Volumes join in the next stage; the structure (one small function per event) leaves room
// for them between intersect() and shading.
#pragma once

#include <cstdint>

#include "core/rgb.h"
#include "core/sampler.h"
#include "scene/scene.h"

namespace caligo {

struct PathSettings {
  int max_depth = 8;           // scattering events; 1 = direct lighting only
  int russian_roulette_depth = 3;  // roulette starts after this many bounces
  int max_null_crossings = 256;    // guards against endless chains of null surfaces
};

// What one camera path contributes to the film and its AOVs.
struct PathSample {
  RGB radiance;
  float alpha = 0.0f;        // 1 when the camera ray hit a visible surface
  float hit_t = kInfinity;   // ray parameter of that first visible hit
  Vec3 normal;               // its shading normal (zero when nothing was hit)
  RGB albedo;                // its material's reflectance
};

struct PathCounters {
  uint64_t rays = 0;         // every Embree query: camera, bounce and shadow rays
};

PathSample trace_path(const Scene& scene, Ray ray, const Sampler& sampler, const PathSettings& settings,
                      PathCounters& counters);

}  // namespace caligo
