// The image of a gobo (projector texture, cookie): linear RGB floats with bilinear lookup
// and wrap addressing. Built from pixels already decoded by the image module (scene loading
// reads files through OpenImageIO; lights/ stays free of file formats). Immutable after
// construction, so one instance is shared by every thread and every frame.
#pragma once

#include <vector>

#include "core/rgb.h"
#include "core/vec.h"

namespace caligo {

class GoboImage {
 public:
  // `pixels` holds width * height values, row 0 at the top of the picture, x fastest.
  // Throws std::invalid_argument for an empty image or a size mismatch.
  GoboImage(int width, int height, std::vector<RGB> pixels);

  // Bilinear lookup at texture coordinates uv; u grows rightwards and v upwards (v = 0 is the
  // bottom row) so a gobo projects upright. Coordinates wrap: lookup(uv + (1, 0)) == lookup(uv).
  RGB lookup(Vec2 uv) const;
  // Mean over the image, for power estimates.
  RGB mean() const { return mean_; }
  int width() const { return width_; }
  int height() const { return height_; }
  RGB pixel(int x, int y) const { return pixels_[static_cast<size_t>(y) * width_ + x]; }
  // Row-major pixels (width() * height()), for lane-parallel lookups that gather from them.
  const RGB* data() const { return pixels_.data(); }

 private:
  int width_, height_;
  std::vector<RGB> pixels_;
  RGB mean_;
};

}  // namespace caligo
