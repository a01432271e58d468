// What one camera path contributes to the film: its radiance split by the kind of light it
// is (the film's light layers add up to the beauty), and what the camera ray first sees.
#pragma once

#include <array>
#include <cstdint>

#include "core/math.h"
#include "core/rgb.h"
#include "core/vec.h"
#include "settings/light_kind.h"

namespace caligo {

// Indexed by LightKind (settings/light_kind.h: the layers and how a contribution is tagged).
struct PathSample {
  std::array<RGB, kLightKindCount> light{};  // indexed by LightKind
  // Coverage: 1 - (what of the background and of holdouts the camera sees through this path).
  float alpha = 0.0f;
  // The first surface the camera ray meets that is seen (not a null boundary), whether or not
  // the path scattered in a medium before it: its ray parameter, shading normal and albedo.
  float hit_t = kInfinity;
  Vec3 normal;
  RGB albedo;

  void add(LightKind kind, RGB value) { light[size_t(kind)] += value; }
  RGB beauty() const {
    RGB sum;
    for (const RGB& l : light) sum += l;
    return sum;
  }
};

}  // namespace caligo
