#include "volumes/volume_scene.h"

namespace caligo {

VolumeScene::VolumeScene(std::vector<VolumePrimitive> primitives) : primitives_(std::move(primitives)) {
  for (const VolumePrimitive& p : primitives_) index_.add(volume_bounds(p.shape));
  index_.commit();
}

void VolumeScene::intervals(const Ray& ray, IntervalScratch& scratch) const {
  scratch.intervals.clear();
  if (primitives_.empty()) return;
  index_.candidates(ray, scratch.candidates);
  for (uint32_t id : scratch.candidates)
    if (const auto range = volume_interval(primitives_[id].shape, ray))
      scratch.intervals.push_back({range->first, range->second, id});
}

}  // namespace caligo
