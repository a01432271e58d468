#include "realtime/sky.h"

#include <vector>

#include "core/parallel.h"
#include "realtime/surface_shading_internal.h"
#include "scene/scene.h"

namespace caligo {

void shade_sky(const GBuffer& gbuffer, const View& camera, const Scene& scene, ColorPlanes& out) {
  std::vector<const EnvironmentLight*> sky;
  for (size_t i = 0; i < scene.desc().lights.size(); ++i)
    if (const auto* env = std::get_if<EnvironmentLight>(&scene.lights()[i]); env && env->visible) sky.push_back(env);
  if (sky.empty()) return;
  const float far = shading::escape_distance(scene);
  parallel_for(gbuffer.depth.height, [&](int y) {
    for (int x = 0; x < gbuffer.depth.width; ++x) {
      if (gbuffer.depth.at(x, y) < kSkyDepth) continue;
      const Ray ray = camera.ray({float(x) + 0.5f, float(y) + 0.5f});
      RGB radiance(0.0f);
      for (const EnvironmentLight* env : sky) radiance += env->escaped(ray.direction);
      if (!radiance.is_black()) radiance *= shading::transmittance(scene.volumes(), ray.origin, ray.at(far));
      out.set(x, y, radiance);
    }
  });
}

}  // namespace caligo
