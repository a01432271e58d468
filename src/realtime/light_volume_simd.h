// light_volume.h's light_volume_interval for 8 camera rays at once, in float: the light's
// solid prepared once per light and frame, tested by core/ray_solids_lanes.h. Lanes flagged
// `unsure` take the scalar light_volume_interval. Read-only after construction (thread-safe).
#pragma once

#include <variant>

#include "core/ray_solids_lanes.h"
#include "realtime/frame_light.h"

namespace caligo {

class LightVolumeLanes {
 public:
  using Batch = lanes::Batch;
  using Mask = lanes::Mask;
  using Result = lanes::Ranges;  // t0, t1 within [0, tmax] where hit; unsure: ask the scalar test

  explicit LightVolumeLanes(const ShadedLight& light);

  // Rays origin + t dir (dir unit), t in [0, tmax], one per lane.
  Result intervals(const lanes::Rays& rays) const;

 private:
  struct Whole {};  // directional lights, infinite ranges
  struct Ball {
    Vec3 centre;
    float radius;
  };
  struct Cone {
    Vec3 apex, axis;
    float cos2;
    std::optional<Ball> range;  // cut by the range sphere when finite
  };
  std::variant<Whole, Ball, Cone, OrientedBox> solid_;
};

}  // namespace caligo
