// The step rules of the decoupled ray marcher (raymarch/march.h) and of the span collection
// tracked rays share: plain data, so that render settings and scene files may hold them.
#pragma once

namespace caligo {

struct MarchSettings {
  float opacity_threshold = 1e-4f;  // stop when max_c T_c falls below this
  // Step size of heterogeneous primitives that set none: this fraction of their bounds' diagonal.
  float auto_step_fraction = 1.0f / 64.0f;
  int max_steps_per_span = 4096;
  // Grid traversal (on in rendering; benchmarks switch them off to measure what they save).
  bool skip_empty_blocks = true;         // off: a grid is one interval over its bounds
  bool constant_blocks_one_step = true;  // off: constant blocks are stepped voxel by voxel
};

}  // namespace caligo
