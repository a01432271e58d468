// Pixel reconstruction filters sampled by importance (filter importance sampling: Ernst et
// al. 2006, "Filter Importance Sampling"; pbrt-v4 FilterSampler; Cycles' filter table).
// Every filter here is non-negative and separable, f(x, y) = f1(x) f1(y), so a sample's film
// position is drawn per axis from the normalised 1D filter and every sample has weight 1:
// the pixel value is the plain mean of its samples, with no weighted splatting.
//
//   box              f1(x) = 1 on [-r, r]                       default r = 0.5 (the pixel)
//   gaussian         f1(x) = max(0, g(x) - g(r)), g = exp(-x^2 / 2 sigma^2)
//                                                               default r = 1.5, sigma = 0.5 (pbrt-v4)
//   blackman_harris  f1(x) = 0.35875 + 0.48829 cos(pi x / r) + 0.14128 cos(2 pi x / r)
//                            + 0.01168 cos(3 pi x / r) on [-r, r]  default r = 0.75 (Cycles' width 1.5)
//
// Offsets and radii are in pixels. Box is sampled analytically; the others through a
// tabulated 1D CDF (kTableSize bins over [-r, r], each bin's mass integrated by Simpson's
// rule), whose piecewise-constant density is what pdf() reports: exactly the density of
// sample_offset(), and within ~1e-5 of the normalised filter.
//
// Use in the render loop (sample s of pixel (x, y), see render/render.cpp):
//   const Vec2 o = filter.sample_offset(sampler.get_2d(sample_dim::kFilm));
//   const Vec2 lens = camera.has_aperture() ? sampler.get_2d(sample_dim::kLens) : Vec2{0.5f, 0.5f};
//   const Ray ray = camera.generate_ray({x + 0.5f + o.x, y + 0.5f + o.y}, lens);
//   film.add(x, y, ...);  // weight 1: the sample belongs to pixel (x, y) only
// A sample may land outside its pixel (r > 0.5); it still counts for pixel (x, y) only,
// which is what makes the estimate the filtered image (each pixel's samples are drawn from
// that pixel's filter).
//
// Thread-safety: immutable after construction; copies share nothing.
#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include "core/vec.h"
#include "settings/pixel_filter_desc.h"

namespace caligo {

class PixelFilter {
 public:
  static constexpr int kTableSize = 1024;

  // Throws std::invalid_argument for a radius outside (0, 16] or a non-positive sigma
  // (the scene parser and the command line check them first, with located errors).
  explicit PixelFilter(const PixelFilterDesc& desc = {});
  static PixelFilter box(float radius = 0.5f);
  static PixelFilter gaussian(float radius = 1.5f, float sigma = 0.5f);
  static PixelFilter blackman_harris(float radius = 0.75f);

  const PixelFilterDesc& desc() const { return desc_; }
  PixelFilterType type() const { return desc_.type; }
  float radius() const { return desc_.radius; }

  // The filter itself, not normalised: f1(x) f1(y); zero outside [-r, r]^2.
  float evaluate(Vec2 offset) const { return evaluate_1d(offset.x) * evaluate_1d(offset.y); }
  float evaluate_1d(float x) const;
  // Density of sample_offset() per square pixel (integrates to 1 over [-r, r]^2).
  float pdf(Vec2 offset) const { return pdf_1d(offset.x) * pdf_1d(offset.y); }
  float pdf_1d(float x) const;
  // Offset from the pixel centre, in [-r, r]^2, distributed as pdf(); u in [0, 1)^2.
  Vec2 sample_offset(Vec2 u) const { return {sample_1d(u.x), sample_1d(u.y)}; }
  float sample_1d(float u) const;

 private:
  PixelFilterDesc desc_;
  std::vector<float> cdf_;  // kTableSize + 1 values from 0 to 1 (empty for box)
};

// "box", "gaussian", "blackman_harris" (and "blackman-harris"); nullopt for other names.
std::optional<PixelFilterType> pixel_filter_type_from_name(std::string_view name);
const char* pixel_filter_name(PixelFilterType type);

}  // namespace caligo
