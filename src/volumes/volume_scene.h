// All volume primitives of a scene and the BVH over their bounds: medium tracking for
// volume primitives. A ray's intervals come back in a caller-owned list (one per thread,
// reused), so finding them does not allocate once the list has grown.
#pragma once

#include <vector>

#include "geometry/bounds_index.h"
#include "volumes/interval.h"
#include "volumes/volume.h"

namespace caligo {

// Per-thread scratch for interval queries.
struct IntervalScratch {
  std::vector<uint32_t> candidates;
  std::vector<VolumeInterval> intervals;
};

class VolumeScene {
 public:
  VolumeScene() = default;
  explicit VolumeScene(std::vector<VolumePrimitive> primitives);

  bool empty() const { return primitives_.empty(); }
  // True when every primitive is homogeneous: marches then need no jitter.
  bool all_homogeneous() const { return all_homogeneous_; }
  const std::vector<VolumePrimitive>& primitives() const { return primitives_; }
  const VolumePrimitive& primitive(uint32_t i) const { return primitives_[i]; }

  // Intervals of every primitive the ray crosses within [tmin, tmax] (already pruned at
  // tmax: pass the nearest opaque surface hit there), in no particular order.
  void intervals(const Ray& ray, IntervalScratch& scratch) const;

 private:
  std::vector<VolumePrimitive> primitives_;
  BoundsIndex index_;
  bool all_homogeneous_ = true;
};

}  // namespace caligo
