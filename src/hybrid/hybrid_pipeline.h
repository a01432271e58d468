// The volumetric methods of Wyman & Ramsey's Table 1 (2008) inside the real-time pipeline
// (realtime/pipeline.h): `caligo realtime --method march|none|brute|hybrid`. A
// HybridScatterer plugs into RealtimePipeline::set_scatterer() and replaces accumulate_light
// for the lights the airlight model covers; everything else of the frame (gather, temporal,
// nearest-depth upsampling, surfaces, composite) is unchanged.
//
// Which lights (the model: an isotropic point light in ONE homogeneous medium, single
// scattering, isotropic phase). A volumetric light takes the method when
//   - it is a PointLight with no IES profile and no finite range;
//   - exactly one volume primitive exists, homogeneous (is_homogeneous()), with a box or sphere
//     shape (convex: each view ray leaves it once), containing both the eye and the light;
//   - its phase is isotropic (IsotropicPhase, or a lobe with g = 0). Anisotropic phases are
//     REJECTED rather than approximated: the airlight integrates 1/(4π) in closed form and an
//     HG lobe of g = 0.3 already changes forward in-scattering by ~2x.
// kTextured is the paper's textured-spotlight method (hybrid/textured_spot.h) for SPOT lights
// (gobo, IES and range included: they go through the path tracer's light profile), in the same
// one-medium setting but with ANY phase: a spot in an anisotropic or coloured medium takes
// Hoffman and Preetham's per-step model in one pass (TexturedSpotSettings::model, kAuto), as
// the paper does for its coloured lights, and the airlight otherwise; with the spot's own shadow volumes cutting each frustum stretch into
// segments sampled at their own rates (every step reads the shadow map when an occluder is
// open); point lights under kTextured take the hybrid.
// Other lights (box and directional lights, spots outside kTextured, other media) keep the
// march, with one note on stderr per light. The medium's bounds cut each ray at its exit (the depth handed to the
// scatter passes is min(opaque depth, exit)): the airlight of a bounded convex medium seen
// and lit from inside is exactly the unbounded one over that segment. Colour: σ_s and σ_t are
// RGB; a grey medium takes one evaluation, a coloured one three (one per channel, exact).
// The march's faked multiple-scattering floor does not apply to these methods.
//
// Occluders (for kHybrid's shadow volumes): every opaque surface of the scene, MeshEdges built
// once at construction. Analytic spheres are tessellated as icospheres (4 subdivisions,
// 5,120 triangles) scaled to CIRCUMSCRIBE the sphere: the volume may then only be larger
// than the shadow the shadow map holds, and inside it the shadow map decides, so the result
// stays exact. An open or non-manifold mesh cannot bound a volume: its bounding box stands in
// (bounding_box_proxy; its shadow holds the mesh's), rays ending inside a volume are then
// marched to their surface (HybridSettings::conservative_tails), and a warning on stderr names
// the geometry and its problem (mesh_edges.h). Shadow volumes are rebuilt when the
// light moves (cached by position).
//
// Thread safety: one scatterer per pipeline; scatter() is called from the pipeline's thread
// and runs its passes on the thread pool.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hybrid/airlight.h"
#include "hybrid/hybrid_scatter.h"
#include "hybrid/mesh_edges.h"
#include "hybrid/shadow_volume.h"
#include "hybrid/textured_spot.h"
#include "realtime/pipeline.h"

namespace caligo {

enum class VolumetricMethod { kMarch, kNone, kBrute, kHybrid, kTextured };

// "march", "none", "brute", "hybrid", "textured"; std::nullopt for anything else.
std::optional<VolumetricMethod> parse_volumetric_method(std::string_view name);
const char* volumetric_method_name(VolumetricMethod method);

// A closed box around `mesh` (slightly larger: a flat mesh still bounds a volume), whose shadow
// volume holds the mesh's own; empty for an empty mesh.
TriangleMesh bounding_box_proxy(const TriangleMesh& mesh);

class HybridScatterer : public LightScatterer {
 public:
  // settings: samples (hybrid, 50) and brute_samples (150) as in the paper.
  HybridScatterer(const Scene& scene, VolumetricMethod method, HybridSettings settings = {},
                  TexturedSpotSettings spot_settings = {});
  ~HybridScatterer() override;

  bool scatter(size_t index, const FrameLight& light, const VolumeScene& volumes, const View& low_view,
               const Plane& low_depth, ColorPlanes& accum) override;

  // The method light `index` used in the last frame (kMarch for lights left to the march or
  // never seen).
  VolumetricMethod used(size_t index) const;
  // Non-empty when some occluder is open or non-manifold: its bounding box then stands in for
  // its shadow volume (bounding_box_proxy), with HybridSettings::conservative_tails.
  const std::string& open_occluder() const { return open_occluder_; }

 private:
  struct CachedVolumes;
  void note(size_t index, const std::string& why);
  // Light `index`'s shadow volumes for a light at `light` (cached while it stands still),
  // rasterised from low_view against `depth`; every visible point lies within light_reach of it.
  ShadowVolumeBuffers shadow_volume_buffers(size_t index, Vec3 light, float light_reach, const View& low_view,
                                            const Plane& depth);
  // The per-channel airlight passes of one light at `position` into `accum`.
  bool scatter_channels(VolumetricMethod method, const ScatteringMedium& medium, Vec3 position, RGB weight,
                        const FrameLight& frame_light, const View& low_view, const Plane& depth,
                        const ShadowVolumeBuffers* buffers, ColorPlanes& accum) const;
  // A spot light: kTextured takes the textured-spotlight pass (hybrid/textured_spot.h).
  bool scatter_spot(size_t index, const SpotLight& spot, const FrameLight& frame_light, const VolumeScene& volumes,
                    const View& low_view, const Plane& low_depth, ColorPlanes& accum);

  VolumetricMethod method_;
  HybridSettings settings_;
  TexturedSpotSettings spot_settings_;
  Bounds3 scene_bounds_;
  std::vector<MeshEdges> occluders_;
  std::string open_occluder_;
  std::vector<VolumetricMethod> used_;
  std::vector<bool> noted_;
  std::vector<CachedVolumes> cache_;
};

}  // namespace caligo
