// Per-pixel sums of path samples and their AOVs, turned into an Image at the end.
// Each pixel is written by exactly one tile, so no locking is needed, and its samples are
// summed in sample-index order, so the result is identical for any thread count.
#pragma once

#include <vector>

#include "image/image.h"
#include "integrators/path_tracer.h"

namespace caligo {

class Film {
 public:
  explicit Film(Vec2i resolution);

  // Adds one sample's values to pixel (x, y); `depth` is its camera-space Z (kInfinity for none).
  void add(int x, int y, const PathSample& s, float depth);
  // Channels: R G B A Z N.X N.Y N.Z albedo.R albedo.G albedo.B. Colour, alpha, normal and
  // albedo are averages over the samples; Z is the nearest depth any sample saw.
  Image resolve(int spp) const;

 private:
  struct Pixel {
    double r = 0, g = 0, b = 0, alpha = 0;
    float nearest_depth = kInfinity;
    Vec3 normal;
    RGB albedo;
  };
  Vec2i resolution_;
  std::vector<Pixel> pixels_;
};

}  // namespace caligo
