// A vertex of a path that guiding trains from: where it is, the direction the path left along and
// that direction's pdf, the throughput after it, and the image's sum when it was made (what the
// path adds after it, over that throughput, is the radiance that arrived along the direction).
#pragma once

#include "core/rgb.h"
#include "core/vec.h"

namespace caligo {

struct GuidedVertex {
  Vec3 x, wi;
  float pdf;         // of the sampling that drew wi (the mixture, or the native alone)
  float f;           // BSDF times cosine, or phase function, at wi (channel average)
  float pdf_native;  // the BSDF's or phase function's own density at wi
  bool surface;
  RGB throughput;
  RGB image_before;
};

}  // namespace caligo
