// Shadow maps of the real-time pipeline: one perspective face for spot lights, a cube
// (6 faces of 90 degrees) for point lights, one orthographic face for box and directional
// lights (the directional face covers the scene's bounds). Depth is linear along each
// face's forward axis; re-rendered only when the light (or the geometry) moves.
//
// Faces: spot lights get one perspective face of 2 x outer angle (a cube when the outer
// angle exceeds 75 degrees); point lights six 90-degree faces (+x, -x, +y, -y, +z, -z),
// looked up by the dominant axis of p - light position; box lights an orthographic face over
// the emitting rectangle with depth measured from it; directional lights an orthographic
// face fitted to the scene bounds and placed just outside them, against the light, or
// cascades: several such faces, each over one range of the camera's depth and looked up by
// the depth of p from the camera (realtime/directional_faces.h).
//
// Bias (why): a lookup returns the depth at the texel centre, while p may lie anywhere in the
// texel, so a surface tilted by theta from the light differs by up to ~0.7 texel * tan(theta).
// The comparison allows `bias` metres plus `texel_bias` texel footprints at p's depth (a
// texel-size-scaled bias: 1.5 covers slopes up to ~65 degrees); shading offsets p along the
// normal by texel_size(p) for steeper ones (normal-offset shadows).
#pragma once

#include <optional>
#include <vector>

#include "core/bounds.h"
#include "realtime/frame_light.h"
#include "realtime/plane.h"
#include "realtime/view.h"

namespace caligo {

class RasterScene;

struct CascadeFaces;

struct ShadowMap {
  std::vector<View> faces;
  std::vector<Plane> depth;  // one per face
  // A directional light's cascades: face i holds the points whose depth along the camera's
  // forward axis from its eye is at most far[i] (the last also those beyond).
  struct Cascades {
    Vec3 eye, forward;
    std::vector<float> far;
    int face(float depth) const {
      int i = 0;
      while (i + 1 < int(far.size()) && depth > far[size_t(i)]) ++i;
      return i;
    }
  };
  std::optional<Cascades> cascades;
  float bias = 1.0e-4f;      // metres of slack in the depth comparison
  float texel_bias = 1.5f;   // extra slack in texel footprints at the lookup depth

  // Surfaces take the 2 x 2 bilinear percentage-closer filter (Reeves et al. 1987, with the
  // bilinear weights of hardware PCF): edges ramp over one texel instead of stair-stepping.
  // false: one tap, as the volumetric march always takes (it averages over its steps).
  bool filter_surfaces = true;

  // 1 where p is lit (not farther than the stored depth + bias), 0 in shadow; points
  // outside every face are lit.
  float visibility(Vec3 p) const;
  // What surfaces see: the four texels around p compared one by one and weighted bilinearly
  // (in [0, 1]), or visibility(p) when !filter_surfaces. Taps outside a single face are lit;
  // a cube face clamps them to its rim.
  float surface_visibility(Vec3 p) const;
  // The face p is looked up in: 0, the cube face of p's dominant axis from the light, or the
  // cascade of p's camera depth.
  int face_index(Vec3 p) const;
  // World size of one texel at p (for normal offsets).
  float texel_size(Vec3 p) const;
  bool is_cube() const { return !cascades && faces.size() == 6; }
  bool single_face() const { return faces.size() == 1; }
};

// std::nullopt when there is nothing to shadow (a directional light over an empty scene).
// skip_emitter >= 0 leaves that scene light's visible surface out (a stand-in inside its own
// emitter: FrameLight::skip_emitter).
std::optional<ShadowMap> render_shadow_map(const RasterScene& scene, const ShadedLight& light, int size,
                                           const Bounds3& scene_bounds, int32_t skip_emitter = -1);
// A directional light's cascades for the frame's `camera` (faces from fit_cascades) into `map`:
// faces `map` already holds unchanged are kept, and of those whose window moved but still
// covers what the frame needs only the nearest is redrawn (the others next frame: a camera
// moving steadily redraws one face a frame, a cut all); a face that is `whole`'s one face
// (end_with_whole_face) is copied from it. Returns the number of faces rendered.
int update_cascaded_shadow_map(const RasterScene& scene, const CascadeFaces& fit, const View& camera,
                               int32_t skip_emitter, ShadowMap& map, const ShadowMap* whole = nullptr);

}  // namespace caligo
