// Where a directional light's shadow-map faces go: one orthographic face over the whole scene,
// or cascades (Engel 2006, "Cascaded shadow maps"; Zhang et al. 2006, "Parallel-split shadow
// maps"), each face covering one range of the camera's depth, so the texels near the camera
// are small and the far ones large, as a game's sun shadows are.
//
// A cascade's window is the square around the bounding sphere of its slice of the camera's
// frustum, widened by a margin and with its centre snapped to a grid of the margin's size
// (Valient 2008, "Stable rendering of cascaded shadow maps"): the sphere's size does not
// change as the camera turns, and the snapped centre moves only after the camera has moved a
// margin's width, so the face, and the map rendered for it, is reused until then and its
// texels never crawl. Each window is clipped to the scene's own window, so a small scene's far
// cascades end where the scene does. Every face's eye plane lies just outside the scene
// against the light, so every caster is in every face.
#pragma once

#include <vector>

#include "core/bounds.h"
#include "realtime/view.h"

namespace caligo {

// Light space of a direction (`forward` along it, `right` and `up` across): the same axes for
// the same direction, frame after frame, as the snapped cascade windows and the light's
// tables (light_depth_volume.h) need. An orthographic view of a unit window at the origin.
View light_basis(Vec3 direction, int size);

// The orthographic face looking along `direction` whose window covers the bounds' corners,
// with its eye plane just in front of all of them.
View fit_directional_face(const Bounds3& bounds, Vec3 direction, int size);

// The far ends of `count` camera-depth ranges from near to far: the practical split (Zhang
// et al. 2006), lambda of the logarithmic split plus 1 - lambda of the uniform one.
std::vector<float> cascade_splits(float near, float far, int count, float lambda);

struct CascadeFaces {
  std::vector<View> faces;  // nearest range first
  std::vector<float> far;   // the camera depth at which each face ends
  // The light-space rectangle (along the faces' right and up axes) each face must cover: its
  // slice's bounding square, clipped to the scene. An older face that still covers it may
  // serve a frame longer (ShadowMap: update_cascaded_shadow_map).
  struct Window {
    float x0, x1, y0, y1;
  };
  std::vector<Window> needed;
};

// Faces whose texels are not smaller than those of `whole` (the light's one face over the
// scene) are replaced, with every farther face, by `whole` itself: a small scene's far
// cascades, clipped to it at half the size, would be coarser than its one face.
void end_with_whole_face(CascadeFaces& fit, const View& whole);

// Does `face` (of the same light) cover the window?
bool covers(const View& face, const CascadeFaces::Window& w);

// The cascades of a directional light along `direction` for the camera `camera` seeing depths
// [near, far]; `scene` bounds the casters (and clips the windows).
CascadeFaces fit_cascades(const View& camera, float near, float far, Vec3 direction, const Bounds3& scene,
                          int count, int size);

}  // namespace caligo
