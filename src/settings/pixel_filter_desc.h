#pragma once

#include <array>

#include "core/enum_names.h"

namespace caligo {

// A pixel reconstruction filter as the scene file gives it; render/pixel_filter.h builds and
// samples it. Radius in pixels (the support is [-radius, radius]^2; Cycles' "filter width"
// is 2 x radius); sigma (gaussian only) in pixels.
enum class PixelFilterType { box, gaussian, blackman_harris };
inline constexpr std::array<EnumName<PixelFilterType>, 4> kPixelFilterNames{
    {{PixelFilterType::box, "box"},
     {PixelFilterType::gaussian, "gaussian"},
     {PixelFilterType::blackman_harris, "blackman_harris"},
     {PixelFilterType::blackman_harris, "blackman-harris"}}};
struct PixelFilterDesc {
  PixelFilterType type = PixelFilterType::box;
  float radius = 0.5f;
  float sigma = 0.5f;
  // The radius a type gets when none is given: box 0.5 (the whole pixel, today's jitter),
  // gaussian 1.5 (pbrt-v4's default, with sigma 0.5), Blackman-Harris 0.75 (Cycles' default
  // filter width of 1.5 pixels).
  static float default_radius(PixelFilterType type) {
    return type == PixelFilterType::box ? 0.5f : (type == PixelFilterType::gaussian ? 1.5f : 0.75f);
  }
};

}  // namespace caligo
