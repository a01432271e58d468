// The render outputs (AOVs) a film can hold, chosen at render time (--aov), and the EXR channel
// names they are written under: the beauty as the root layer R, G, B (what every reader shows
// first), alpha as A, depth as Z, and every other output as a layer "name.R/G/B" (or .X/.Y/.Z)
// -- the "layer.channel" form Nuke shows as a layer and Blender as a pass.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "settings/light_kind.h"

namespace caligo {

enum class Aov : uint8_t {
  kAlpha,
  kDepth,
  kNormal,
  kAlbedo,
  // The light layers, one per LightKind and in its order (they add up to the beauty): the
  // values follow from the kinds, so the two lists cannot drift apart.
  kSurfaceDirect = 4 + uint8_t(LightKind::kSurfaceDirect),
  kSurfaceIndirect = 4 + uint8_t(LightKind::kSurfaceIndirect),
  kVolumeDirect = 4 + uint8_t(LightKind::kVolumeDirect),
  kVolumeIndirect = 4 + uint8_t(LightKind::kVolumeIndirect),
  kSurfaceEmission = 4 + uint8_t(LightKind::kSurfaceEmission),
  kVolumeEmission = 4 + uint8_t(LightKind::kVolumeEmission),
  kBackground = 4 + uint8_t(LightKind::kBackground),
  // The variance of each pixel's mean, per channel of the beauty: (sum x^2 / n - mean^2) / (n - 1),
  // for denoisers and for --target-rmse, which estimates the image's error from it.
  kVariance = 4 + kLightKindCount,
  // Each pixel's sample count (one channel, "samples"): where adaptive sampling spent them.
  kSamples,
};
inline constexpr int kAovCount = int(Aov::kSamples) + 1;

constexpr Aov light_aov(LightKind kind) { return Aov(int(Aov::kSurfaceDirect) + int(kind)); }

// The beauty is always there; this says which of the others are.
class AovSet {
 public:
  constexpr AovSet() = default;
  // alpha, depth, normal and albedo: what the film held before light layers existed.
  static constexpr AovSet defaults() {
    return AovSet{}.with(Aov::kAlpha).with(Aov::kDepth).with(Aov::kNormal).with(Aov::kAlbedo);
  }
  static constexpr AovSet all() {
    AovSet s;
    s.bits_ = (1u << kAovCount) - 1u;
    return s;
  }
  // A comma-separated list of names (aov_name), plus "beauty" (always on), "lights" (the seven
  // light layers), "default" and "all". Throws InputError naming the unknown entry.
  static AovSet parse(std::string_view list);

  constexpr AovSet with(Aov a) const {
    AovSet s = *this;
    s.bits_ |= 1u << unsigned(a);
    return s;
  }
  constexpr bool has(Aov a) const { return (bits_ >> unsigned(a)) & 1u; }
  constexpr uint32_t bits() const { return bits_; }
  static constexpr AovSet from_bits(uint32_t bits) {
    AovSet s;
    s.bits_ = bits & ((1u << kAovCount) - 1u);
    return s;
  }
  friend constexpr bool operator==(AovSet, AovSet) = default;

 private:
  uint32_t bits_ = 0;
};

// The user-facing name (--aov and the EXR layer): "alpha", "depth", "normal", "albedo",
// "surface_direct", ..., "background".
std::string_view aov_name(Aov a);

// The EXR channel names of the beauty plus the selected AOVs, in the order Film::resolve writes
// them.
std::vector<std::string> aov_channels(AovSet set);

}  // namespace caligo
