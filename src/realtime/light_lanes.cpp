#include "realtime/light_lanes.h"

#include <cmath>

#include "core/overloaded.h"

namespace caligo {
namespace {

float inverse_range(float range) { return std::isfinite(range) ? 1.0f / range : 0.0f; }

}  // namespace

LightLanes::LightLanes(const ShadedLight& light) {
  std::visit(Overloaded{[&](const PointLight& l) {
                          kind_ = Kind::point;
                          position_ = l.position;
                          range_ = l.range;
                          color_ = l.intensity;
                          if (l.ies.profile) ies_.emplace(l.ies);
                        },
                        [&](const SpotLight& l) {
                          kind_ = Kind::spot;
                          position_ = l.position;
                          direction_ = l.direction;
                          cos_inner_ = l.cos_inner;
                          cos_outer_ = l.cos_outer;
                          range_ = l.range;
                          color_ = l.intensity;
                          if (l.ies.profile) ies_.emplace(l.ies);
                          if (l.gobo.image) spot_gobo_.emplace(l);
                        },
                        [&](const BoxLight& l) {
                          kind_ = Kind::box;
                          position_ = l.position;
                          direction_ = l.direction;
                          up_ = l.up;
                          right_ = cross(l.direction, l.up);
                          half_width_ = l.half_width;
                          half_height_ = l.half_height;
                          range_ = l.range;
                          color_ = l.irradiance;
                          if (l.gobo.image) box_gobo_.emplace(l.gobo);
                        },
                        [&](const DirectionalLight& l) {
                          kind_ = Kind::directional;
                          direction_ = l.direction;
                          color_ = l.irradiance;
                        }},
             light);
  inv_range_ = kind_ == Kind::box ? 0.0f : inverse_range(range_);
}

}  // namespace caligo
