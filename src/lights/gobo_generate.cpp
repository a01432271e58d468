#include "lights/gobo_generate.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/math.h"
#include "core/rng.h"

namespace caligo {
namespace {

constexpr int kCells = 24;                // stained-glass panes
constexpr float kLeadValue = 0.02f;       // the leading and the rim: almost opaque
constexpr float kPaneLuminance = 0.3f;    // every pane's luminance
constexpr float kPaneSaturation = 0.75f;  // HSV saturation: pure blue at this saturation still reaches 0.3
constexpr float kRimRadius = 0.48f;       // the window's radius, in image widths
constexpr float kLeadHalfWidth = 0.006f;  // in image widths
constexpr int kBars = 8;                  // white bars across the image
constexpr int kChecks = 8;                // checker squares per side

// A uniform number in [0, 1) from (seed, index, salt).
float unit_hash(uint32_t seed, uint32_t index, uint32_t salt) {
  return float(hash_values(seed, index, salt) >> 40) * 0x1p-24f;
}

// Fully bright HSV colour of hue h in [0, 1) and saturation s.
RGB hsv_colour(float h, float s) {
  const auto channel = [&](float n) {
    const float k = std::fmod(n + 6.0f * h, 6.0f);
    return 1.0f - s * std::clamp(std::min(k, 4.0f - k), 0.0f, 1.0f);
  };
  return {channel(5.0f), channel(3.0f), channel(1.0f)};
}

// A saturated colour of luminance kPaneLuminance: the HSV colour scaled down (never up past 1:
// blue, the darkest hue, reaches kPaneLuminance at scale ~1).
RGB pane_colour(float hue) {
  const RGB c = hsv_colour(hue, kPaneSaturation);
  return c * std::min(kPaneLuminance / c.luminance(), 1.0f / c.max_component());
}

float distance_squared(Vec2 a, Vec2 b) { return sqr(a.x - b.x) + sqr(a.y - b.y); }

struct Pane {
  Vec2 site;
  RGB colour;
};

std::vector<Pane> panes(uint32_t seed) {
  std::vector<Pane> result;
  for (uint32_t i = 0; i < kCells; ++i)
    result.push_back({{unit_hash(seed, i, 0), unit_hash(seed, i, 1)}, pane_colour(unit_hash(seed, i, 2))});
  return result;
}

// The pane at p, or the lead when p lies within half_width of the border between its
// nearest and second-nearest sites (the distance to their bisector) or outside the rim.
RGB stained_glass_at(Vec2 p, const std::vector<Pane>& panes, float half_width) {
  if (distance_squared(p, {0.5f, 0.5f}) > sqr(kRimRadius)) return RGB(kLeadValue);
  size_t first = 0, second = 1;
  float d_first = kInfinity, d_second = kInfinity;  // squared distances
  for (size_t i = 0; i < panes.size(); ++i) {
    const float d = distance_squared(p, panes[i].site);
    if (d < d_first) {
      second = first, d_second = d_first;
      first = i, d_first = d;
    } else if (d < d_second) {
      second = i, d_second = d;
    }
  }
  const float between = std::sqrt(distance_squared(panes[first].site, panes[second].site));
  const float to_border = (d_second - d_first) / (2.0f * std::max(between, 1e-6f));
  return to_border < half_width ? RGB(kLeadValue) : panes[first].colour;
}

// The white fraction of each texel [x, x + 1] / n of a row crossed by `periods` white/black
// stripe pairs, white first: white on [k, k + 1/2) / periods.
std::vector<double> stripe_coverage(int n, int periods) {
  const auto covered_up_to = [periods](double t) {  // the white length in [0, t]
    const double cells = t * periods;
    return (std::floor(cells) * 0.5 + std::min(cells - std::floor(cells), 0.5)) / periods;
  };
  std::vector<double> coverage;
  for (int x = 0; x < n; ++x) {
    const double white = (covered_up_to(double(x + 1) / n) - covered_up_to(double(x) / n)) * n;
    coverage.push_back(std::clamp(white, 0.0, 1.0));  // rounding may stray by 1e-15
  }
  return coverage;
}

}  // namespace

std::optional<GoboPattern> parse_gobo_pattern(std::string_view name) {
  if (name == "stained_glass") return GoboPattern::kStainedGlass;
  if (name == "bars") return GoboPattern::kBars;
  if (name == "checker") return GoboPattern::kChecker;
  return std::nullopt;
}

GoboImage generate_gobo(GoboPattern kind, int resolution, uint32_t seed) {
  if (resolution < kMinGoboResolution || resolution > kMaxGoboResolution)
    throw std::invalid_argument("generate_gobo: resolution outside [8, 4096]");
  const int n = resolution;
  const std::vector<double> bars = stripe_coverage(n, kBars), checks = stripe_coverage(n, kChecks / 2);
  const std::vector<Pane> glass = kind == GoboPattern::kStainedGlass ? panes(seed) : std::vector<Pane>{};
  const float half_width = std::max(kLeadHalfWidth, 1.0f / float(n));

  std::vector<RGB> pixels(size_t(n) * size_t(n));
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      RGB& out = pixels[size_t(y) * size_t(n) + size_t(x)];
      switch (kind) {
        case GoboPattern::kStainedGlass:
          out = stained_glass_at({(x + 0.5f) / float(n), (y + 0.5f) / float(n)}, glass, half_width);
          break;
        case GoboPattern::kBars:
          out = RGB(float(bars[size_t(x)]));
          break;
        case GoboPattern::kChecker: {  // white where the row and column stripes agree
          const double cx = checks[size_t(x)], cy = checks[size_t(y)];
          out = RGB(float(cx * cy + (1.0 - cx) * (1.0 - cy)));
          break;
        }
      }
    }
  }
  return GoboImage(n, n, std::move(pixels));
}

}  // namespace caligo
