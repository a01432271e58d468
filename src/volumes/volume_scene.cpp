#include "volumes/volume_scene.h"

namespace caligo {

VolumeScene::VolumeScene(std::vector<VolumePrimitive> primitives) : primitives_(std::move(primitives)) {
  for (const VolumePrimitive& p : primitives_) {
    index_.add(volume_bounds(p.shape));
    all_homogeneous_ = all_homogeneous_ && is_homogeneous(p.shader);
  }
  index_.commit();
}

// Below this many primitives, testing each one directly is cheaper than a BVH traversal
// (a user-geometry traversal costs more than a few analytic interval tests).
constexpr size_t kLinearScanLimit = 8;

void VolumeScene::intervals(const Ray& ray, VolumeContext& context) const {
  context.intervals.clear();
  if (primitives_.size() <= kLinearScanLimit) {
    for (uint32_t id = 0; id < primitives_.size(); ++id) append_intervals(primitives_[id], id, ray, context);
    return;
  }
  index_.candidates(ray, context.candidates);
  for (uint32_t id : context.candidates) append_intervals(primitives_[id], id, ray, context);
}

}  // namespace caligo
