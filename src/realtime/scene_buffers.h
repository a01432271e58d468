// Full-resolution scene buffers of a frame: linear depth, normals and material per pixel,
// made either by the tiled SIMD software rasteriser over the scene's triangles (analytic
// spheres tessellated) or by Embree rays; docs/techniques.md has the measured comparison.
#pragma once

#include <cstdint>
#include <vector>

#include "core/bounds.h"
#include "realtime/plane.h"
#include "realtime/view.h"

namespace caligo {

class Scene;

// Depth of pixels that see nothing (the sky). Finite so that the passes' arithmetic never
// meets inf - inf; far beyond any scene (sizes are capped at 10,000 km).
inline constexpr float kSkyDepth = 1.0e9f;

struct GBuffer {
  Plane depth;                    // linear depth along the view's forward axis; kSkyDepth for none
  Plane nx, ny, nz;               // unit shading normal facing the viewer; 0 where nothing
  std::vector<int32_t> material;  // index into Scene::materials(); -1 where nothing
  // 1 where the viewer sees the side of the geometric normal (one-sided emitters glow
  // only there), 0 for back faces and where nothing.
  std::vector<uint8_t> front;
};

// The scene's opaque triangles in world space, laid out for the rasteriser. Null-material
// surfaces are left out (the path tracer's rays pass through them too); emitters are kept.
//
// Analytic spheres become UV spheres of kSphereSegments x kSphereRings quads (4,032
// triangles, inscribed): the chord sagitta is R (1 - cos(pi / 64)) = 0.0012 R per
// direction, so depth differs from the true sphere by at most ~0.25 % of R, and vertex
// normals are the analytic ones.
class RasterScene {
 public:
  static constexpr int kSphereSegments = 64;  // around the pole axis
  static constexpr int kSphereRings = 32;     // pole to pole

  // Which surfaces: every one the light sees (shadow maps: glass occludes direct light, as a
  // path tracer's shadow ray through a dielectric finds), those the camera sees as surfaces
  // (glass left out, so what lies behind it shows), or the glass alone (its transmission).
  enum class Layer { all, opaque, glass };
  static RasterScene build(const Scene& scene, Layer layer = Layer::all);
  // One triangle in world space with unit shading normals at its vertices; material indexes
  // Scene::materials(); emitter the scene light whose visible surface it is, or -1.
  // Degenerate (zero-area) triangles are dropped.
  void add_triangle(Vec3 p0, Vec3 p1, Vec3 p2, Vec3 n0, Vec3 n1, Vec3 n2, int32_t material, int32_t emitter = -1);

  size_t triangle_count() const { return materials_.size(); }
  const Vec3* vertices(size_t t) const { return &positions_[3 * t]; }
  const Vec3* vertex_normals(size_t t) const { return &normals_[3 * t]; }
  Vec3 geometric_normal(size_t t) const { return geometric_normals_[t]; }  // cross(p1 - p0, p2 - p0), unit
  int32_t material(size_t t) const { return materials_[t]; }
  int32_t emitter(size_t t) const { return emitters_[t]; }
  const Bounds3& bounds() const { return bounds_; }

 private:
  std::vector<Vec3> positions_;  // 3 per triangle, not indexed: the set-up reads them in order
  std::vector<Vec3> normals_;    // 3 per triangle
  std::vector<Vec3> geometric_normals_;
  std::vector<int32_t> materials_;
  std::vector<int32_t> emitters_;
  Bounds3 bounds_;
};

// `simd = false` runs the scalar edge-function loop; both give bit-identical buffers.
GBuffer rasterize_gbuffer(const RasterScene& scene, const View& view, bool simd = true);
// The same into `out`, reusing its storage when the size matches (no per-frame allocation
// or clearing of ~21 bytes per pixel).
void rasterize_gbuffer(const RasterScene& scene, const View& view, GBuffer& out, bool simd = true);
// Depth only (shadow maps): the same rasteriser without normals or materials.
// skip_emitter >= 0 leaves out that light's visible surface (a stand-in's shadow map).
Plane rasterize_depth(const RasterScene& scene, const View& view, bool simd = true, int32_t skip_emitter = -1);
// The same buffers from Embree primary rays (one per pixel centre), for comparison.
GBuffer trace_gbuffer(const Scene& scene, const View& view);

// Per pixel of `view`, what the glass (a RasterScene::Layer::glass scene) in front of the
// opaque surfaces at `opaque_depth` lets through: (1 - F)^2 at the nearest glass face
// (realtime/glass.cpp), 1 where no glass is in front.
Plane glass_transmission(const RasterScene& glass, const Scene& scene, const View& view, const Plane& opaque_depth);

}  // namespace caligo
