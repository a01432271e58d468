#include "integrators/visibility.h"

#include <cmath>

#include "raymarch/march.h"

namespace caligo {

// Shadow rays stop this fraction short of an area-light sample so they do not hit the light.
constexpr float kShadowEpsilon = 1e-4f;

RGB light_transmittance(const Scene& scene, Vec3 origin, Vec3 sampled_from, const LightSample& ls,
                        bool casts_shadows, float jitter, PathScratch& scratch, PathCounters& counters) {
  Ray shadow{origin, ls.wi, 0.0f, kInfinity};
  if (std::isfinite(ls.distance)) {
    shadow.direction = sampled_from + ls.wi * ls.distance - origin;
    shadow.tmax = 1.0f - kShadowEpsilon;
  }
  if (casts_shadows) {
    ++counters.rays;
    if (scene.surfaces().occluded(shadow)) return RGB(0.0f);
  }
  if (scene.volumes().empty()) return RGB(1.0f);
  return march_transmittance(scene.volumes(), shadow, jitter, scratch.march_settings, scratch.march);
}

}  // namespace caligo
