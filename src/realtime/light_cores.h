// Light cores resolved (docs/techniques.md, "The error users see with the defaults"): around a
// point light or a spot's apex seen in fog, single scattering rises as 1/D for rays passing at
// distance D from the light, a peak narrower than an accumulation pixel and narrower than one
// output pixel at its centre. The low-resolution, pixel-centred, interleaved march flattens it
// and the gather and upsample spread what is left. This pass re-marches the output pixels
// within `radius` of each such light's projection at full resolution: rays spread over the
// pixel's area (as the path tracer's film averages it; `subpixels` x `subpixels` within 2 pixels
// of the light, where the peak varies inside a pixel, 2 x 2 within 6, one beyond), each marching
// every marched light with `samples` equiangular steps at their midpoints, no interleaving; the
// result replaces the upsampled value there.
//
// Only for frames whose lights all take the march (a LightScatterer's lights are not in it).
#pragma once

#include <vector>

#include "realtime/frame_light.h"
#include "realtime/plane.h"
#include "realtime/view.h"
#include "settings/realtime_settings.h"
#include "volumes/volume_scene.h"

namespace caligo {

// The cores' radius, in accumulation pixels (x RealtimeSettings::scale for the frame's pixels):
// the upsample and gather spread a core over about this many. The pipeline resolves, and
// reference_error reports, this radius.
inline constexpr float kLightCoreRadius = 6.0f;

struct LightCoreSettings {
  float radius = 12.0f;  // output pixels
  int subpixels = 4;     // rays per pixel: subpixels^2
  int samples = 32;      // equiangular steps per ray and light
};

// The pixels of a view whose centres lie within `radius` pixels of a projected point (View::project:
// pixel x, y, depth), none when it lies behind the camera; with each pixel, its distance.
struct DiscPixel {
  Vec2i pixel;
  float distance;
};
std::vector<DiscPixel> disc_pixels(Vec2i resolution, Vec3 projected, float radius);

// Returns the number of pixels resolved. `depth` is the full-resolution linear depth
// (kSkyDepth for none), `volumetric` the upsampled buffer at the view's resolution.
int resolve_light_cores(const std::vector<FrameLight>& lights, const VolumeScene& volumes, const View& view,
                        const Plane& depth, const AccumulationSettings& accumulation,
                        const LightCoreSettings& settings, ColorPlanes& volumetric);

}  // namespace caligo
