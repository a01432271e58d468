// All volume primitives of a scene and the BVH over their bounds: medium tracking for
// volume primitives. A ray's majorant intervals come back in the caller's per-thread
// VolumeContext, so finding them does not allocate once its lists have grown.
//
// Beside the primitives it holds the scene's surface-bounded media (materials' interiors) as
// primitives of UnboundedVolumeShape, outside the BVH: which one a ray is in is the medium
// stack's business (media/medium_stack.h), and the caller names it per query. Their ids follow
// the primitives' (medium m is primitive primitives().size() + m).
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
  // `media`: the media surfaces enclose, one slot each (Scene::medium_entry maps a material's
  // interior to its slot); an entry whose shape is not
  // UnboundedVolumeShape or that is not homogeneous throws std::invalid_argument.
  explicit VolumeScene(std::vector<VolumePrimitive> primitives, std::vector<VolumePrimitive> media = {});

  // No primitives (media may exist: a ray in one still needs marching).
  bool empty() const { return primitives_.empty(); }
  bool has_media() const { return !media_.empty(); }
  // True when every primitive is homogeneous: marches then need no jitter.
  bool all_homogeneous() const { return all_homogeneous_; }
  const std::vector<VolumePrimitive>& primitives() const { return primitives_; }
  // A primitive or (ids from primitives().size() on) a medium.
  const VolumePrimitive& primitive(uint32_t i) const {
    return i < primitives_.size() ? primitives_[i] : media_[i - primitives_.size()];
  }

  // Replaces context.intervals with the majorant intervals of every primitive the ray crosses
  // within [tmin, tmax] (already pruned at tmax: pass the nearest opaque surface hit there),
  // and, when medium >= 0, the whole [tmin, tmax] of that scene medium (the ray is in it).
  // Each primitive's intervals are in order along the ray; primitives in no particular order.
  void intervals(const Ray& ray, VolumeContext& context, int medium = -1) const;

 private:
  std::vector<VolumePrimitive> primitives_;
  std::vector<VolumePrimitive> media_;
  BoundsIndex index_;
  bool all_homogeneous_ = true;
};

}  // namespace caligo
