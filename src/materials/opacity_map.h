// Partly transparent surfaces (cards for leaves, hair or fur inside a volume): a material's
// opacity, a number or a greyscale texture over the surface's texture coordinates. A surface of
// opacity a is a layer that a fraction a of the light meets (its BSDF) and 1 - a passes straight
// through; the decoupled march stores such layers in the TransmittanceRecord as steps of
// transmittance (raymarch/transmittance_record.h), so camera, shadow and bounce rays see them
// without restarting the march.
#pragma once

#include <vector>

#include "core/vec.h"

namespace caligo {

// A greyscale texture of values in [0, 1], rows top to bottom; uv (0, 0) is the bottom-left
// corner (the OBJ and glTF-to-OpenGL convention), v up. Lookups wrap (repeat) and interpolate
// bilinearly between texel centres.
class OpacityMap {
 public:
  // Requires width, height > 0 and width * height values.
  OpacityMap(int width, int height, std::vector<float> values);
  float lookup(Vec2 uv) const;
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  float texel(int x, int y) const;
  int width_, height_;
  std::vector<float> values_;
};

}  // namespace caligo
