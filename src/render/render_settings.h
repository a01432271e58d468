// Everything that says how to render (as opposed to what): passed by value, never global.
#pragma once

#include <cstdint>

#include "core/vec.h"
#include "integrators/path_tracer.h"
#include "raymarch/march.h"

namespace caligo {

struct RenderSettings {
  Vec2i resolution{640, 480};
  int spp = 16;
  int max_depth = 8;
  int max_volume_bounces = 128;
  DistanceSampling distance_sampling = DistanceSampling::kMis;
  bool absorption_by_weight = true;  // PathSettings::absorption_by_weight
  int deferred_nee = 0;              // PathSettings::deferred_nee
  LightSamplerKind light_sampler = LightSamplerKind::kTree;  // PathSettings::light_sampler
  uint64_t seed = 0;
  int threads = 0;  // 0: all hardware threads
  int tile_size = 16;
  MarchSettings march;  // step rules of the decoupled ray marcher
};

}  // namespace caligo
