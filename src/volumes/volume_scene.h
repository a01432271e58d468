// All volume primitives of a scene and the BVH over their bounds: medium tracking for
// volume primitives. A ray's majorant intervals come back in the caller's per-thread
// VolumeContext, so finding them does not allocate once its lists have grown.
#pragma once

#include <vector>

#include "geometry/bounds_index.h"
#include "volumes/interval.h"
#include "volumes/volume.h"
#include "volumes/volume_context.h"

namespace caligo {

class VolumeScene {
 public:
  VolumeScene() = default;
  explicit VolumeScene(std::vector<VolumePrimitive> primitives);

  bool empty() const { return primitives_.empty(); }
  // True when every primitive is homogeneous: marches then need no jitter.
  bool all_homogeneous() const { return all_homogeneous_; }
  const std::vector<VolumePrimitive>& primitives() const { return primitives_; }
  const VolumePrimitive& primitive(uint32_t i) const { return primitives_[i]; }

  // Replaces context.intervals with the majorant intervals of every primitive the ray crosses
  // within [tmin, tmax] (already pruned at tmax: pass the nearest opaque surface hit there).
  // Each primitive's intervals are in order along the ray; primitives in no particular order.
  void intervals(const Ray& ray, VolumeContext& context) const;

 private:
  std::vector<VolumePrimitive> primitives_;
  BoundsIndex index_;
  bool all_homogeneous_ = true;
};

}  // namespace caligo
