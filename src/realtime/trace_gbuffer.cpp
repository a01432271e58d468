// The G-buffer from Embree primary rays: the rasteriser's reference and its competitor.
// One ray per pixel centre; null surfaces are stepped over exactly as the path tracer's
// camera rays do.
#include "core/parallel.h"
#include "realtime/scene_buffers.h"
#include "scene/scene.h"

namespace caligo {

GBuffer trace_gbuffer(const Scene& scene, const View& view) {
  const int w = view.resolution.x, h = view.resolution.y;
  GBuffer g;
  g.depth = Plane(w, h, kSkyDepth);
  g.nx = Plane(w, h);
  g.ny = Plane(w, h);
  g.nz = Plane(w, h);
  g.material.assign(size_t(w) * size_t(h), -1);
  g.front.assign(g.material.size(), 0);
  parallel_for_tiles(make_tiles(view.resolution, 32), [&](const Tile& tile) {
    for (int y = tile.y0; y < tile.y1; ++y)
      for (int x = tile.x0; x < tile.x1; ++x) {
        const Ray ray = view.ray({float(x) + 0.5f, float(y) + 0.5f});
        const auto hit = nearest_non_null_hit(scene, ray);
        if (!hit) continue;
        const SurfaceInteraction si = scene.interaction(ray, *hit);
        const size_t pixel = size_t(y) * size_t(w) + size_t(x);
        const bool front = dot(si.ng, ray.direction) < 0.0f;
        const Vec3 ng = front ? si.ng : -si.ng;
        const Vec3 n = dot(si.ns, ng) < 0.0f ? -si.ns : si.ns;
        g.depth.data[pixel] = hit->t * view.depth_per_t(ray.direction);
        g.nx.data[pixel] = n.x;
        g.ny.data[pixel] = n.y;
        g.nz.data[pixel] = n.z;
        g.material[pixel] = int32_t(si.material - scene.materials().data());
        g.front[pixel] = front ? 1 : 0;
      }
  });
  return g;
}

}  // namespace caligo
