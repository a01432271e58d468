// An environment map: a latitude-longitude (equirectangular) image of the radiance arriving
// from every direction, with the 2D piecewise-constant distribution that importance-samples
// it (pbrt-v3 section 14.2.4, "Infinite Area Lights"; Cycles' background map).
//
// Convention (in the map's own frame; EnvironmentLight's rotation turns it about +Y):
//   u = 0.5 + atan2(w.x, -w.z) / (2 pi),   v = acos(w.y) / pi,   +Y up.
// Pixel (x, y) covers u in [x, x+1) / width and v in [y, y+1) / height, row 0 at the top (the
// zenith, +Y). The image centre looks along -Z, u = 0.75 along +X, u = 0 = 1 along +Z: seen
// from inside the sphere the picture is not mirrored (what Blender, Cycles and pbrt show for
// an equirectangular image, up to the choice of axes). Any aspect ratio is accepted; images
// that are not 2:1 are stretched to cover the sphere.
//
// Lookup is bilinear between pixel centres, wrapping in u and clamping in v (a pole row
// blends only with itself across the pole).
//
// Sampling: one cell (pixel) is chosen with probability ∝ F * Omega, where F is the cell's
// mean luminance under the bilinear lookup (the pixel's luminance filtered by
// (1/8, 3/4, 1/8) in x and y, exact for the lookup above) and Omega the cell's solid angle;
// marginal over rows, conditional over the columns of a row. Inside the cell the direction is
// uniform in phi and in cos(theta), so the solid-angle pdf is F / sum(F * Omega): constant
// over the cell, exactly proportional to the filtered luminance, finite at the poles, and for
// a constant map exactly 1 / (4 pi). (This deviates from pbrt's uniform-in-(u, v) cell, whose
// pdf_uv / (2 pi^2 sin(theta)) grows without bound towards the poles.) F > 0 wherever the
// lookup is > 0, so every direction that carries light can be sampled (unbiased MIS).
// Zero-luminance cells and rows have zero probability; an all-black map cannot be sampled
// (sample returns nullopt, pdf 0).
//
// Immutable after construction: one instance is shared by every thread.
#pragma once

#include <optional>
#include <vector>

#include "core/math.h"
#include "core/rgb.h"
#include "core/sampling.h"
#include "core/vec.h"

namespace caligo {

// The lat-long convention above, for unit directions; both wrap u into [0, 1).
Vec2 direction_to_latlong(Vec3 w);
Vec3 latlong_to_direction(Vec2 uv);

struct EnvironmentSample {
  Vec3 w;     // unit, in the map's frame
  float pdf;  // solid angle
};

class EnvironmentMap {
 public:
  // `pixels` holds width * height linear RGB values, row 0 at the top, x fastest. Throws
  // std::invalid_argument for an empty image, a size mismatch, a negative or non-finite value,
  // or values so large that the map's integral overflows a float.
  EnvironmentMap(int width, int height, std::vector<RGB> pixels);

  int width() const { return width_; }
  int height() const { return height_; }
  RGB pixel(int x, int y) const { return pixels_[size_t(y) * size_t(width_) + size_t(x)]; }

  // Radiance from the unit direction w (map frame), bilinear.
  RGB lookup(Vec3 w) const;
  // A direction with probability density (solid angle) pdf(w); nullopt for a black map.
  std::optional<EnvironmentSample> sample(Vec2 u) const;
  float pdf(Vec3 w) const;

  // The integral of the pixels over the sphere, sum(pixel * Omega) in W m^-2 (each pixel
  // constant over its cell), and that divided by 4 pi: the mean radiance.
  RGB integral() const { return integral_; }
  RGB mean() const { return integral_ * kInv4Pi; }
  bool is_black() const { return marginal_.empty(); }

 private:
  void build_distribution();
  int cell_x(float u) const;
  int cell_y(float v) const;

  int width_, height_;
  std::vector<RGB> pixels_;
  RGB integral_;
  std::vector<double> cos_edge_;  // cos(theta) at the top edge of each row, height + 1 entries
  std::vector<float> cell_solid_angle_;  // per row
  DiscreteDistribution marginal_;  // over rows; empty for a black map
  std::vector<DiscreteDistribution> conditional_;  // over the columns of each row
};

}  // namespace caligo
