// The reference ladder's images (reference.h): per-pixel means of a rung over jittered
// camera rays.
#include "integrators/reference.h"

#include <algorithm>
#include <vector>

#include "core/parallel.h"
#include "integrators/reference_internal.h"

namespace caligo {

using namespace reference_detail;

std::vector<RGB> reference_image(const Scene& scene, Vec2i resolution, const ReferenceOptions& options) {
  const Camera camera = scene.camera(resolution);
  std::vector<RGB> pixels(size_t(resolution.x) * size_t(resolution.y));
  parallel_for(resolution.y, [&](int y) {
    for (int x = 0; x < resolution.x; ++x) {
      Pcg32 rng(hash_values(options.seed, uint64_t(x), uint64_t(y)), 0x5eed);
      double r = 0, g = 0, b = 0;
      for (int s = 0; s < options.samples_per_pixel; ++s) {
        const Vec2 jitter = next_2d(rng);
        // The lens sample is drawn only for a thin lens, so pinhole images keep their random stream.
        const Vec2 lens = camera.has_aperture() ? next_2d(rng) : Vec2{0.5f, 0.5f};
        const Ray ray = camera.generate_ray({float(x) + jitter.x, float(y) + jitter.y}, lens);
        const RGB v = options.estimator == ReferenceEstimator::kSingleScattering
                          ? reference_single_scattering(scene, ray, options.distance_samples, rng)
                          : reference_delta_tracking(scene, ray, options.limits, rng);
        r += v.r, g += v.g, b += v.b;
      }
      const double n = std::max(1, options.samples_per_pixel);
      pixels[size_t(y) * size_t(resolution.x) + size_t(x)] = RGB(float(r / n), float(g / n), float(b / n));
    }
  });
  return pixels;
}

RGB reference_mean_radiance(const Scene& scene, Vec2i resolution, const ReferenceOptions& options) {
  double r = 0, g = 0, b = 0;
  const std::vector<RGB> pixels = reference_image(scene, resolution, options);
  for (const RGB& p : pixels) r += p.r, g += p.g, b += p.b;
  const double n = double(std::max<size_t>(1, pixels.size()));
  return RGB(float(r / n), float(g / n), float(b / n));
}

RGB reference_mean_radiance(const Scene& scene, Vec2i resolution, int samples_per_pixel,
                            ReferenceEstimator which, uint64_t seed) {
  ReferenceOptions options;
  options.estimator = which;
  options.samples_per_pixel = samples_per_pixel;
  options.seed = seed;
  return reference_mean_radiance(scene, resolution, options);
}

}  // namespace caligo
