// The wrapper around Embree 3 for surfaces (geometry/bounds_index.h is the other Embree user,
// a BVH over boxes). Everything Caligo asks of surfaces goes through here: closest hit, occlusion (shadow rays) and all hits along a ray (for
// nested media and mesh volumes). Embree types stay in embree_scene.cpp.
//
// Input is validated before Embree sees it: Embree silently drops triangles with NaN or
// infinite vertices, which would turn a broken mesh into a silently wrong image.
//
// Thread safety: build (add_*, commit) on one thread; after commit() every query is const
// and may run concurrently. Geometry ids are dense: the n-th geometry added has id n.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "core/bounds.h"
#include "core/ray.h"
#include "geometry/shapes.h"
#include "geometry/triangle_mesh.h"

namespace caligo {

struct SurfaceHit {
  float t = 0.0f;
  uint32_t geom_id = 0;
  uint32_t prim_id = 0;
  Vec2 uv;  // barycentrics (b1, b2) for triangles; unused for spheres
  Vec3 ng;  // unit geometric normal: outward for spheres, cross(p1-p0, p2-p0) side for triangles
};

class EmbreeScene {
 public:
  EmbreeScene();
  ~EmbreeScene();
  EmbreeScene(EmbreeScene&&) noexcept;
  EmbreeScene& operator=(EmbreeScene&&) noexcept;

  // Throws std::invalid_argument with validate_mesh()'s message if the mesh is unusable.
  uint32_t add_mesh(TriangleMesh mesh);
  uint32_t add_sphere(const Sphere& sphere);
  // Shadow rays pass through this geometry (null / transparent surfaces).
  void set_casts_shadows(uint32_t geom_id, bool casts);
  void commit();

  std::optional<SurfaceHit> intersect(const Ray& ray) const;
  // True when something that casts shadows lies on the ray within [tmin, tmax).
  bool occluded(const Ray& ray) const;
  // The same, except that hits on geometry g with deferred[g] != 0 do not block: they are
  // appended to `deferred_hits` (unsorted; t, ids and geometric normal) for the caller to resolve
  // (shadow rays through nested media). When it returns true the list is incomplete.
  bool occluded(const Ray& ray, const std::vector<uint8_t>& deferred, std::vector<SurfaceHit>& deferred_hits) const;
  // Every surface crossing in [tmin, tmax), sorted by t. `out` is cleared first; reuse it
  // across rays so the query does not allocate once it has grown.
  void all_hits(const Ray& ray, std::vector<SurfaceHit>& out) const;

  size_t geometry_count() const;
  bool is_sphere(uint32_t geom_id) const;
  const TriangleMesh& mesh(uint32_t geom_id) const;  // requires !is_sphere(geom_id)
  const Sphere& sphere(uint32_t geom_id) const;      // requires is_sphere(geom_id)
  Bounds3 bounds() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace caligo
