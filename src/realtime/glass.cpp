// Glass in the real-time frame: the camera sees through it to the surfaces and fog behind,
// through its two interfaces. Refraction, reflection and the interior's absorption are the
// path tracer's; what a game's forward-rendered glass does cheaply is kept: each glass pixel
// passes (1 - F(cos theta))^2 of the light behind it, F the dielectric Fresnel reflectance at
// the front face's angle (materials/bsdf.h, the path tracer's own), taken again for the exit.
// The composite multiplies the whole pixel by it, the fog between the camera and the glass
// included (the volumetric buffer is not split at the glass): a slight darkening of that fog.
#include <cmath>

#include "core/parallel.h"
#include "materials/bsdf.h"
#include "realtime/scene_buffers.h"
#include "scene/scene.h"

namespace caligo {

Plane glass_transmission(const RasterScene& glass, const Scene& scene, const View& view, const Plane& opaque_depth) {
  const GBuffer g = rasterize_gbuffer(glass, view);
  Plane out(opaque_depth.width, opaque_depth.height, 1.0f);
  parallel_for(out.height, [&](int y) {
    for (int x = 0; x < out.width; ++x) {
      const size_t i = size_t(y) * size_t(out.width) + size_t(x);
      if (g.material[i] < 0 || !(g.depth.data[i] < opaque_depth.data[i])) continue;
      const auto* bsdf = std::get_if<DielectricBsdf>(&scene.materials()[size_t(g.material[i])].bsdf);
      if (!bsdf) continue;
      const Vec3 wo = -view.ray({float(x) + 0.5f, float(y) + 0.5f}).direction;
      const float cos_i = std::abs(dot(wo, Vec3(g.nx.data[i], g.ny.data[i], g.nz.data[i])));
      const float t = 1.0f - fresnel_dielectric(cos_i, bsdf->ior);
      out.data[i] = t * t;
    }
  });
  return out;
}

}  // namespace caligo
