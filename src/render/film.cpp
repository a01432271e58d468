#include "render/film.h"

#include <algorithm>

namespace caligo {

Film::Film(Vec2i resolution)
    : resolution_(resolution), pixels_(size_t(resolution.x) * size_t(resolution.y)) {}

void Film::add(int x, int y, const PathSample& s, float depth) {
  Pixel& p = pixels_[size_t(y) * size_t(resolution_.x) + size_t(x)];
  // A non-finite sample would poison the pixel forever; it is dropped (and is a bug to find).
  if (s.radiance.is_finite()) {
    p.r += s.radiance.r;
    p.g += s.radiance.g;
    p.b += s.radiance.b;
  }
  p.alpha += s.alpha;
  p.nearest_depth = std::min(p.nearest_depth, depth);
  p.normal += s.normal;
  p.albedo += s.albedo;
}

Image Film::resolve(int spp) const {
  Image image(resolution_.x, resolution_.y,
              {"R", "G", "B", "A", "Z", "N.X", "N.Y", "N.Z", "albedo.R", "albedo.G", "albedo.B"});
  const double inv = 1.0 / double(spp);
  for (int y = 0; y < resolution_.y; ++y)
    for (int x = 0; x < resolution_.x; ++x) {
      const Pixel& p = pixels_[size_t(y) * size_t(resolution_.x) + size_t(x)];
      const float values[] = {float(p.r * inv),        float(p.g * inv),        float(p.b * inv),
                              float(p.alpha * inv),    p.nearest_depth,         p.normal.x * float(inv),
                              p.normal.y * float(inv), p.normal.z * float(inv), p.albedo.r * float(inv),
                              p.albedo.g * float(inv), p.albedo.b * float(inv)};
      for (int c = 0; c < 11; ++c) image.at(x, y, c) = values[c];
    }
  return image;
}

}  // namespace caligo
