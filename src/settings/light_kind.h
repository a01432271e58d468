// The light layers a render separates its light into (render AOVs, integrators/path_sample.h),
// defined once: the path tracer classifies by them, the film's outputs are named after them.
#pragma once

#include <cstdint>
#include <string_view>

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

// The layer's name (--aov, the EXR layer): "surface_direct", ..., "background". The switch has
// no default, so a new kind does not compile (-Wswitch) until it has a name.
constexpr std::string_view light_kind_name(LightKind kind) {
  switch (kind) {
    case LightKind::kSurfaceDirect: return "surface_direct";
    case LightKind::kSurfaceIndirect: return "surface_indirect";
    case LightKind::kVolumeDirect: return "volume_direct";
    case LightKind::kVolumeIndirect: return "volume_indirect";
    case LightKind::kSurfaceEmission: return "surface_emission";
    case LightKind::kVolumeEmission: return "volume_emission";
    case LightKind::kBackground: return "background";
  }
  return "?";
}

}  // namespace caligo
