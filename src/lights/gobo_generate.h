// Procedural gobo images, for scenes that cannot ship an image file (the built-ins): a
// stained-glass window, vertical bars and a checkerboard. Deterministic for a given
// (pattern, resolution, seed) on every platform: positions and colours come from integer
// hashes, not from a library RNG. Square images, linear RGB, every value in [0, 1].
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "lights/gobo.h"

namespace caligo {

enum class GoboPattern {
  kStainedGlass,  // ~24 Voronoi cells of saturated colours of about equal luminance (0.3),
                  // dark leading (0.02) between them and outside a circle of radius 0.48
  kBars,          // 8 white vertical bars on black, the first starting at the left edge
  kChecker,       // 8x8 black/white squares, white at the top-left
};

inline constexpr int kMinGoboResolution = 8;
inline constexpr int kMaxGoboResolution = 4096;

// "stained_glass", "bars", "checker".
std::optional<GoboPattern> parse_gobo_pattern(std::string_view name);

// A resolution x resolution image. Bars and checker are box-filtered exactly (a texel
// straddling an edge is grey), so their mean is 1/2 at any resolution; the stained glass is
// point-sampled at texel centres, and its leading is about 0.012 of the image wide (at least
// two texels) whatever the resolution. Throws std::invalid_argument for a resolution outside
// [kMinGoboResolution, kMaxGoboResolution].
GoboImage generate_gobo(GoboPattern kind, int resolution, uint32_t seed);

}  // namespace caligo
