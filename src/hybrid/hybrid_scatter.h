// The per-pixel scattering pass of Wyman and Ramsey's hybrid (2008) for one point light in a
// homogeneous single-scattering medium, and the brute-force ray march it is measured against.
//
// Both passes compute the same quantity: the in-scattered radiance reaching the eye along each
// pixel's view ray (through the pixel centre) from the eye to the opaque surface, single
// scattering, isotropic phase, no surface shading, no attenuation of the surface (the caller
// adds e^{-σ_t t} L_surface):
//
//   L = color · intensity · σ_s / (4π) ∫_0^{t_opaque} V(x(t)) e^{-σ_t (t + d(t))} / d(t)² dt,
//
// with V the light's visibility from the shadow map. Neither pass samples the integrand: the
// ray is cut into steps, each step's visibility is read once from the shadow map, and every
// lit stretch is integrated in closed form with the airlight model (airlight.h), so the only
// error is where along a step visibility changes. Consecutive lit steps telescope into one
// interval (T(a) - T(b)), so the closed form is evaluated only where visibility changes.
//
//   - scatter_brute: `brute_samples` equal steps over the whole ray [0, t_end] (the paper's
//     baseline, one shadow-map lookup per step);
//   - scatter_hybrid: the shadow-volume buffers (shadow_volume.h) say where shadow can be.
//     Pixels with no volume surface in front of the opaque depth (and the eye outside every
//     volume) are lit along the whole ray: one closed-form evaluation, no lookups. Otherwise
//     [0, front) is lit (eye outside every volume), [front, back] is marched with `samples`
//     steps, and [back, t_end] is lit iff no volume contains the ray beyond `back`.
//
// Sky pixels (opaque depth >= kSkyDepth) and very far surfaces: the march ends at
// `max_distance`, beyond which the ray is taken as lit (the shadow volumes end at their far
// caps; set max_distance to where they end or beyond the scene). The hybrid clamps front and
// back into [0, t_end] the same way, so both passes integrate the same ray.
//
// Units: world metres, intensity in W/sr, σ in 1/m; `opaque_depth` is LINEAR depth along the
// view's forward axis (GBuffer::depth / rasterize_depth, kSkyDepth for none), converted per pixel
// to the ray distance t = depth / dot(direction, forward). Thread safety: pure; rows run on the
// thread pool.
#pragma once

#include <cstdint>
#include <vector>

#include "core/rgb.h"
#include "hybrid/airlight.h"
#include "hybrid/shadow_volume.h"
#include "realtime/plane.h"
#include "realtime/shadow_map.h"
#include "realtime/view.h"

namespace caligo {

struct HybridLight {
  Vec3 position;
  float intensity = 1.0f;  // W/sr
  RGB color{1.0f};         // multiplies the scalar airlight (the model is linear in intensity)
};

struct HybridSettings {
  int samples = 50;         // hybrid: steps over [front, back]
  int brute_samples = 150;  // brute force: steps over [0, t_end]
  // Where in a step visibility is read: the midpoint moved by jitter · (n - 0.5) steps, n a
  // per-pixel interleaved-gradient noise in [0, 1) (0 = midpoints; 1 = anywhere in the step).
  // Dither trades the banding of a fixed step pattern for noise.
  float jitter = 0.5f;
  float max_distance = 1000.0f;  // metres; the march ends here (see above)
  // Lit runs by Wyman & Ramsey's per-frame table (FrameAirlight: one lookup per end) where it
  // is accurate, σ_t D <= kFrameTableMaxDepth for the light at distance D from the eye, in a
  // perspective view; by the closed-form tail (airlight_tail) elsewhere, and everywhere when
  // false, the default: on this CPU the table's per-pixel setup and its lookup (an atan2 and a
  // fourth root) cost more than the tail's (bench_hybrid: the hybrid pass 22 % slower at 1024²).
  bool frame_table = false;
  // Set by the pipeline when some shadow volume is a proxy's (an open occluder's bounding box):
  // a ray whose end lies in a volume is then marched with the shadow map up to its surface, not
  // taken as shadowed beyond the last volume surface (true only of exact volumes).
  bool conservative_tails = false;
};

// FrameAirlight's error relative to a pixel's whole-ray airlight is 0.6 % at σ_t D = 5 and 4 %
// at 20 (hybrid/airlight.h); past 5 the tail is the accurate choice.
inline constexpr float kFrameTableMaxDepth = 5.0f;

struct ScatterResult {
  ColorPlanes radiance;
  std::vector<int32_t> lookups;  // shadow-map lookups per pixel, row-major
  int64_t total_lookups = 0;
  int marched_pixels = 0;  // pixels that looked up the shadow map at all

  int32_t lookups_at(int x, int y) const { return lookups[size_t(y) * size_t(radiance.width()) + size_t(x)]; }
};

// `opaque_depth` must have view.resolution (std::invalid_argument otherwise), as must
// `volumes` for the hybrid.
ScatterResult scatter_brute(const View& view, const Plane& opaque_depth, const ShadowMap& shadow,
                            const AirlightTable& table, const AirlightMedium& medium,
                            const HybridLight& light, const HybridSettings& settings = {});

ScatterResult scatter_hybrid(const View& view, const Plane& opaque_depth, const ShadowVolumeBuffers& volumes,
                             const ShadowMap& shadow, const AirlightTable& table,
                             const AirlightMedium& medium, const HybridLight& light,
                             const HybridSettings& settings = {});

// The airlight with no shadows at all (every pixel's whole ray lit), the same per-pixel
// closed form the hybrid uses for uncovered pixels.
ColorPlanes scatter_unshadowed(const View& view, const Plane& opaque_depth, const AirlightTable& table,
                               const AirlightMedium& medium, const HybridLight& light,
                               const HybridSettings& settings = {});

}  // namespace caligo
