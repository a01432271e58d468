// What one camera path contributes to the film: its radiance split by the kind of light it
// is (the film's light layers add up to the beauty), and what the camera ray first sees.
#pragma once

#include <array>
#include <cstdint>

#include "core/math.h"
#include "core/rgb.h"
#include "core/vec.h"

namespace caligo {

// Every contribution is tagged where it is added, by how many NON-SPECULAR scattering events
// the path has had up to and including the one that receives the light (mirror and glass
// events do not count: what is seen through them is seen directly):
//   0 events: what the camera sees directly -- emission of a surface, of a medium, or the
//             background (environment and infinite lights);
//   1 event:  direct light, by where that event happened (surface or medium), whether it came
//             by next-event estimation or by hitting the emitter;
//   2 or more: indirect light, by where the FIRST event happened (light that reached a
//             surface by way of fog is surface indirect, as Cycles and Arnold classify it).
enum class LightKind : uint8_t {
  kSurfaceDirect,
  kSurfaceIndirect,
  kVolumeDirect,
  kVolumeIndirect,
  kSurfaceEmission,
  kVolumeEmission,
  kBackground,
};
inline constexpr int kLightKindCount = 7;

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
