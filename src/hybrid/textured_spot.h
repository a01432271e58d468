// The scattering pass of Wyman and Ramsey's textured spotlights (2008, §5): single scattering
// of one SpotLight whose gobo (projector texture) colours the light, in a homogeneous medium,
// marched only where the ray is inside the light's frustum.
//
// Quantity (as in hybrid_scatter.h, which it complements for spot lights): the in-scattered
// radiance along each pixel's centre ray from the eye to the opaque surface, phase p (isotropic
// for the airlight model), no surface term,
//
//   L = σ_s ∫ V(x) E(x) p(θ) e^{-σ_t (t + d)} / d² dt,   E(x) = I · cone · window · IES · gobo,
//
// E the spot's emitted colour towards x (lights/light_profile.h: the same cone, range window,
// IES and gobo functions the path tracer's delta_arrival uses), d the distance to the light.
//
// The pass:
//   - the ray's stretch inside the spot (light_volume_interval: the outer cone cut by the range
//     sphere), clipped to [0, min(opaque, max_distance)]; a pixel whose ray misses it costs
//     nothing (no lookups, zero radiance);
//   - that stretch is cut into n equal steps with
//         n = round(min_steps + (max_steps - min_steps) · sin α),
//     α the angle between the ray and the spot axis (|cos α| = |dot(dir, axis)|). Why: a ray
//     nearly parallel to the axis runs along the cone for a long stretch over which the light
//     direction, hence the texture coordinate, barely changes (the gobo uv depends only on the
//     direction from the light), so few steps suffice; a ray crossing the cone transversally
//     sweeps the whole texture in a short stretch and needs many;
//   - each step reads E and the shadow map once, at the step's midpoint moved by
//     jitter · (noise - 0.5) steps (noise: per-pixel interleaved gradient noise), so the step
//     pattern differs between neighbouring pixels and no sampling planes show. E · V is held
//     constant over the step, whose integral the model (TexturedSpotSettings::model) gives:
//       * the airlight (Sun et al., airlight.h): the step's airlight of an isotropic point light
//         of unit intensity at the spot's position, in closed form (consecutive steps share
//         their endpoint tails, k + 1 tail evaluations per segment of k steps); exact in 1/d²
//         and e^{-σ_t d}, so the only errors are E and V varying inside a step; isotropic
//         phase, one channel per pass;
//       * Hoffman and Preetham (hoffman_preetham.h), the paper's model for its coloured and
//         textured lights: the light at the midpoint, I(ω) e^{-σ_t d} / d², and the phase
//         there, held over the step, times the closed-form ∫ σ_s e^{-σ_t t} dt; any phase, RGB
//         coefficients in one pass; 1/d² varying inside a step is a further error (largest
//         next to the apex, where the steps are long against d).
//     kAuto takes the airlight for a grey, isotropic medium and Hoffman–Preetham otherwise
//     (an anisotropic phase, which the airlight cannot represent, or a coloured medium, which
//     it would march three times).
//   - with the spot's shadow volumes (shadow_volume.h, built from the spot's position), the
//     stretch is cut at the front-most and back-most volume surfaces into before / inside /
//     after, each sampled at its own rate: inside, n steps per stretch length with a shadow
//     lookup each; before and after (lit: the eye outside every volume, and for "after" no
//     volume holding the tail) lit_rate x n per stretch length with no shadow lookups, since
//     there only the gobo varies and its blurred copy varies slowly; after the back-most
//     surface with a volume holding the tail, nothing (in shadow up to the surface). A pixel no
//     volume covers takes the "before" rate over its whole stretch. Each segment has at least
//     one step; lit_rate = 1 gives the stretch's own rate everywhere.
//
// Blur (an approximation): the paper stands in for multiple scattering by lighting the medium
// with a blurred copy of the texture (in-scattered light has been spread over neighbouring
// directions). We build a box-filtered mip chain of the gobo image and use level `blur_level`
// (clamped to the coarsest) for the volumetric term; bilinear lookup with the gobo's own
// rotation and offset. With `blur_per_interval` (the default, the paper's per-interval blur) a
// step reads the level its own footprint asks for when that is coarser: the angle the step
// subtends at the light, in texels of the gobo (log2, rounded down), so a coarse step reads the
// texture's average over what it spans instead of one point of it (which aliases). blur_level 0
// without per-interval blur is the exact single-scattering texture, the one the path tracer
// uses; any blur is NOT what the path tracer computes (it keeps total flux close, since a box
// filter preserves the mean, but moves colour between shafts).
//
// Sky pixels and far surfaces: the march ends at max_distance; the spot's light beyond it is
// dropped (a finite range bounds it anyway). Units: metres, W/sr, 1/m. `opaque_depth` is LINEAR
// depth (GBuffer::depth / rasterize_depth, kSkyDepth for none). Thread safety: pure; rows run on
// the thread pool.
#pragma once

#include <memory>
#include <vector>

#include "hybrid/airlight.h"
#include "hybrid/hoffman_preetham.h"
#include "hybrid/hybrid_scatter.h"
#include "hybrid/shadow_volume.h"
#include "lights/gobo.h"
#include "lights/light.h"
#include "realtime/plane.h"
#include "realtime/shadow_map.h"
#include "realtime/view.h"

namespace caligo {

// How a step's in-scattering is integrated (the header comment): kAuto is the airlight for a
// grey, isotropic medium and Hoffman–Preetham otherwise.
enum class SpotScatterModel { kAuto, kAirlight, kHoffmanPreetham };

struct TexturedSpotSettings {
  SpotScatterModel model = SpotScatterModel::kAuto;
  int min_steps = 16;   // rays along the axis (clamped to >= 1)
  int max_steps = 150;  // rays across the axis (clamped to >= min_steps)
  float jitter = 0.5f;  // 0 = step midpoints; 1 = anywhere in the step
  int blur_level = 2;   // mip level of the gobo for the volumetric term; 0 = exact
  bool blur_per_interval = true;  // coarser where a step spans more than a texel (see above)
  float max_distance = 1000.0f;
  // With shadow volumes: the rate of the stretches outside them (before the front-most surface
  // and, when lit, after the back-most), relative to the stretch inside. Those stretches need
  // no shadow lookups and only follow the (blurred) gobo; see the header comment.
  float lit_rate = 0.5f;
};

// The box-filtered mip chain of `image`: level 0 is a copy, each next level half the size
// (at least 1 texel; each target texel averages a block of source texels, the blocks partitioning
// the source: even sizes keep the mean exactly, odd ones nearly), down to 1x1 or `max_levels` levels.
std::vector<GoboImage> gobo_mip_chain(const GoboImage& image, int max_levels = 16);

// The whole chain as shared images (level 0 the image itself), for a caller that keeps it
// between frames.
using GoboMips = std::vector<std::shared_ptr<const GoboImage>>;
GoboMips gobo_mips(const std::shared_ptr<const GoboImage>& image);

// The steps the pass takes for a ray at |cos α| = abs_cos_axis (the rule above).
int textured_spot_steps(float abs_cos_axis, const TexturedSpotSettings& settings);

// The airlight pass of one channel (σ_s, σ_t scalars, isotropic phase); settings.model is not read.
// `opaque_depth` must have view.resolution, and `volumes`, when given, too (std::invalid_argument
// otherwise). `shadow` may be null (no occlusion; `volumes` is then ignored). `volumes`: the
// spot's shadow volumes from the eye (shadow_volume.h), or null to read the shadow map at every
// step. ScatterResult::lookups counts steps: each reads the gobo once, and the shadow map once
// when the step lies between the volumes (every step, without volumes).
ScatterResult scatter_textured_spot(const View& view, const Plane& opaque_depth, const ShadowMap* shadow,
                                    const AirlightTable& table, const AirlightMedium& medium,
                                    const SpotLight& light, const TexturedSpotSettings& settings = {},
                                    const ShadowVolumeBuffers* volumes = nullptr,
                                    const GoboMips* mips = nullptr);

// The model `model` resolves to for `medium` (kAuto as above; the others as they are).
SpotScatterModel resolve_spot_model(SpotScatterModel model, const ScatteringMedium& medium);

// The pass for a whole medium, by settings.model: Hoffman–Preetham in one pass, or the airlight
// once for a grey medium and once per channel otherwise (ScatterResult::lookups then adds the
// passes' steps). The airlight with an anisotropic phase is a caller's bug (std::invalid_argument).
ScatterResult scatter_textured_spot(const View& view, const Plane& opaque_depth, const ShadowMap* shadow,
                                    const ScatteringMedium& medium, const SpotLight& light,
                                    const TexturedSpotSettings& settings = {},
                                    const ShadowVolumeBuffers* volumes = nullptr, const GoboMips* mips = nullptr);

}  // namespace caligo
