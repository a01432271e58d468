// Shadow volumes of closed occluder meshes for a point light, and their rasterisation from
// the eye into per-pixel front-most and back-most distances (Wyman & Ramsey 2008, section
// 4: the hybrid marches only between these two distances).
//
// Geometry. The volume of a closed occluder is bounded by
//   - the near cap: the occluder's light-facing triangles, as they are;
//   - the sides: each silhouette edge (a, b) extruded away from the light into the quad
//     (b, a, a', b'), where p' = p + extrusion * (p - light) / |p - light|;
//   - the far cap: the light-facing triangles' extruded copies, winding reversed.
// Every vertex p has exactly one extruded copy p', computed once, so faces that share an
// edge share its vertices bit for bit: the volume is watertight and outward-wound, which
// the rasteriser's exact edge rule turns into exact crossing counts. We extrude by a finite
// length rather than to infinity (w = 0) because the CPU rasteriser and the ray-casting
// tests want finite vertices; choose the length with extrusion_for() so the far cap lies
// beyond every surface of the scene (sky pixels then see the far cap, which bounds the
// marched interval). The occluder must be closed (MeshEdges::closed()); see mesh_edges.h
// for what happens to open meshes.
//
// Eye pass. The near cap coincides with the occluder's lit surface, which the opaque depth
// buffer already holds, so it never lies strictly in front of the visible surface: it is
// left out of the pass by default (ShadowVolumeOptions::near_caps). The sides and the far
// cap are rasterised with the real-time rasteriser's set-up (realtime/raster_setup.h:
// near-plane and guard-band clipping, exact shared-edge coverage) and a loop over full-width
// bands of rows (8 pixels at a time) that keeps,
// per pixel, the nearest and farthest surface in front of the opaque depth and the signed
// number of crossings (+1 entering a volume through a face turned to the eye, -1 leaving).
//
// Camera inside a volume. volumes_containing() counts the signed crossings of the segment
// from the eye to the light (which lies outside every volume) with the volume's faces: the
// winding number of the eye. When the eye is inside any volume the marched interval starts
// at t = 0.
//
// Units: world metres; t is the distance along View::ray()'s unit direction. Thread safety:
// the functions are pure; rasterize_shadow_volumes() runs bands of rows on the thread pool.
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "core/bounds.h"
#include "geometry/triangle_mesh.h"
#include "hybrid/mesh_edges.h"
#include "realtime/plane.h"
#include "realtime/view.h"

namespace caligo {

struct ShadowVolume {
  // positions: the occluder's welded vertices, then their extruded copies (vertex i's copy
  // is vertex_count + i). indices: the sides, then the near cap, then the far cap.
  TriangleMesh mesh;
  size_t side_triangles = 0, near_cap_triangles = 0, far_cap_triangles = 0;
  Vec3 light;
  float extrusion = 0.0f;
  Bounds3 occluder_bounds;     // bounds of the near cap (the occluder's lit triangles)
  float min_far_distance = 0;  // the nearest far-cap vertex's distance to the light

  size_t side_begin() const { return 0; }
  size_t near_cap_begin() const { return side_triangles; }
  size_t far_cap_begin() const { return side_triangles + near_cap_triangles; }
};

// Requires occluder.closed() (throws std::invalid_argument otherwise: the caller checks and
// falls back) and extrusion > 0.
ShadowVolume build_shadow_volume(const MeshEdges& occluder, Vec3 light, float extrusion);

// An extrusion length that carries every silhouette past the far side of `scene_bounds`:
// the bounds' diagonal plus the light's distance from them, plus 1 % and a metre.
float extrusion_for(const Bounds3& scene_bounds, Vec3 light);

// The winding number of `point` with respect to the volume: 1 inside, 0 outside (for a
// closed occluder). Robust to the segment grazing an edge (it retries towards points
// jittered around the light).
int volumes_containing(const ShadowVolume& volume, Vec3 point);

// "No shadow-volume surface in front of the opaque surface" in front and back.
inline constexpr float kNoShadowVolume = std::numeric_limits<float>::infinity();

struct ShadowVolumeBuffers {
  // Per pixel, the view-ray distance t of the nearest (front) and farthest (back) shadow
  // volume surface strictly in front of the opaque surface. When the eye is inside a volume
  // front is 0 (and back is at least 0). kNoShadowVolume in both when the pixel needs no
  // marching: the eye is outside every volume and no surface covers the pixel in front of
  // the opaque depth.
  Plane front, back;
  // Per pixel, how many volumes contain the view ray beyond `back` (up to the opaque
  // surface): 0 means that last segment is lit. Before `front` the ray is lit unless
  // eye_count > 0 (then front = 0 and there is no such segment).
  std::vector<int32_t> tail_count;
  int eye_count = 0;  // volumes containing the eye

  bool covered(int x, int y) const { return front.at(x, y) != kNoShadowVolume; }
  int32_t tail(int x, int y) const { return tail_count[size_t(y) * size_t(front.width) + size_t(x)]; }
};

struct ShadowVolumeOptions {
  // Rasterise the near caps too; needed only when the occluders are NOT in opaque_depth.
  bool near_caps = false;
  // The far caps bound the volume for pixels that see the sky through it; leave them out
  // only when every such pixel has an opaque surface nearer than the extrusion.
  bool far_caps = true;
  // A surface counts when its depth < opaque depth * (1 - depth_bias): a side quad meets
  // the lit occluder surface at a grazing angle along the silhouette, and must not count
  // as "in front" of it there by rounding.
  float depth_bias = 1.0e-4f;
  // The band loop 8 pixels at a time (AVX2); false: one at a time. Identical buffers.
  bool simd = true;
};

// One pass over all the volumes. `opaque_depth` is the linear depth of the view's pixels
// (GBuffer::depth, kSkyDepth where nothing) at view.resolution; a size mismatch throws
// std::invalid_argument.
ShadowVolumeBuffers rasterize_shadow_volumes(std::span<const ShadowVolume> volumes, const View& view,
                                             const Plane& opaque_depth,
                                             const ShadowVolumeOptions& options = {});

}  // namespace caligo
