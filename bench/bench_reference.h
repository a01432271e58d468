// What the equal-time benchmarks share: a converged reference cached in the build folder (delete
// the file after changing the scene or the integrator) and the error of an image against it.
#pragma once

#include <filesystem>
#include <string>

#include "core/vec.h"
#include "image/compare.h"
#include "image/exr_io.h"
#include "image/image.h"

namespace caligo::bench {

// The reference named `stem`_WxH_SPP.exr in the build folder's bench/ cache, rendered by
// render_reference() (returning an Image) when the file is not there yet.
template <typename RenderFn>
Image cached_reference(const std::string& stem, Vec2i resolution, int spp, RenderFn&& render_reference) {
  // Built piecewise: GCC 12 warns falsely (-Wrestrict) about "literal" + std::string.
  std::string name = stem;
  for (const std::string& part : {std::string("_"), std::to_string(resolution.x), std::string("x"),
                                  std::to_string(resolution.y), std::string("_"), std::to_string(spp),
                                  std::string(".exr")})
    name += part;
  const std::filesystem::path cache = std::filesystem::path(CALIGO_BENCH_CACHE_DIR) / name;
  if (std::filesystem::exists(cache)) return read_exr(cache.string());
  const Image rendered = render_reference();
  write_exr(cache.string(), rendered);
  return rendered;
}

// The mean squared error of `image` against `reference` (what MSE x time compares).
inline double mse(const Image& image, const Image& reference) {
  const double rmse = compare_images(image, reference).rmse;
  return rmse * rmse;
}

}  // namespace caligo::bench
