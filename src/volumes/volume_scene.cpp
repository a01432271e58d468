#include "volumes/volume_scene.h"

#include <stdexcept>
#include <variant>

namespace caligo {

VolumeScene::VolumeScene(std::vector<VolumePrimitive> primitives, std::vector<VolumePrimitive> media)
    : primitives_(std::move(primitives)), media_(std::move(media)) {
  for (const VolumePrimitive& p : primitives_) {
    index_.add(volume_bounds(p.shape));
    all_homogeneous_ = all_homogeneous_ && is_homogeneous(p.shader);
  }
  index_.commit();
  for (const VolumePrimitive& m : media_)
    if (!std::holds_alternative<UnboundedVolumeShape>(m.shape) || !is_homogeneous(m.shader))
      throw std::invalid_argument("a surface-bounded medium must be unbounded and homogeneous");
}

// Below this many primitives, testing each one directly is cheaper than a BVH traversal
// (a user-geometry traversal costs more than a few analytic interval tests).
constexpr size_t kLinearScanLimit = 8;

void VolumeScene::intervals(const Ray& ray, VolumeContext& context, int medium) const {
  context.intervals.clear();
  if (medium >= 0 && size_t(medium) < media_.size())
    append_intervals(media_[size_t(medium)], uint32_t(primitives_.size()) + uint32_t(medium), ray, context);
  if (primitives_.size() <= kLinearScanLimit) {
    for (uint32_t id = 0; id < primitives_.size(); ++id) append_intervals(primitives_[id], id, ray, context);
    return;
  }
  index_.candidates(ray, context.candidates);
  for (uint32_t id : context.candidates) append_intervals(primitives_[id], id, ray, context);
}

}  // namespace caligo
