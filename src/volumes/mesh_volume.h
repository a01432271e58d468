// The inside of a closed triangle mesh as a volume primitive's shape. Kulla (the seed): "mesh
// defined volumes require counting intersections (even or odd)", with a bounding-box check
// deciding whether a ray starts inside. Here every ray is answered from scratch, with no
// history: all crossings of the ray's line are collected from where the line enters the
// mesh's (padded) bounding box, a point that is certainly outside, and paired by even/odd
// counting. Nested surfaces therefore make shells, and orientation does not matter.
//
// Robustness: Embree's triangle test includes the edges, so a ray through an edge or vertex
// shared by several triangles reports each of them at (nearly) the same t, and a ray in a
// face's plane may miss it. A query whose hits are not all well apart, or whose crossing
// count along the whole box is odd, is therefore repeated on a slightly perturbed ray (a
// ~1e-5 to 1e-3 fraction of the box), which generically misses every edge; the intervals
// then move by about that much, far below what a medium's boundary can show.
//
// Thread safety: build on one thread; intervals() is const and may run concurrently with
// each thread passing its own `hits` scratch.
#pragma once

#include <memory>
#include <utility>
#include <vector>

#include "core/bounds.h"
#include "core/error.h"
#include "core/ray.h"
#include "geometry/embree_scene.h"
#include "geometry/triangle_mesh.h"

namespace caligo {

class MeshVolume {
 public:
  // `mesh` is in world space. Throws InputError at `where` when the mesh cannot bound a
  // volume: validate_mesh() problems, or an edge (after welding vertices with equal positions)
  // not shared by exactly two triangles, naming its vertex indices and how many triangles use
  // it. Inconsistently oriented triangles are accepted: even/odd counting ignores orientation.
  // With `require_closed` false the closure check is skipped (an open mesh read by parity, as
  // Cycles reads one): a ray through a hole crosses the surface an odd number of times, and
  // its unmatched last crossing is dropped.
  static std::shared_ptr<const MeshVolume> build(TriangleMesh mesh, const SourceLocation& where,
                                                 bool require_closed = true);
  // Why `mesh` is not a closed surface (its first bad edge and how many there are), or empty.
  static std::string closure_problem(const TriangleMesh& mesh);

  Bounds3 bounds() const { return bounds_; }
  const TriangleMesh& mesh() const { return scene_.mesh(0); }

  // Appends to `out` the stretches of [ray.tmin, ray.tmax] inside the mesh: ordered, disjoint,
  // each non-empty. `hits` is per-thread scratch (no allocation once it has grown). The
  // direction need not be unit length; t is the ray's parameter.
  void intervals(const Ray& ray, std::vector<SurfaceHit>& hits,
                 std::vector<RayRange>& out) const;

  // How many Embree queries intervals() makes for `ray`: 1, or more when the ray passes
  // through an edge or vertex and is perturbed (for tests and diagnostics).
  int query_count(const Ray& ray, std::vector<SurfaceHit>& hits) const;

 private:
  MeshVolume(EmbreeScene scene, Bounds3 bounds);
  // Fills `hits` with the crossings of the ray's line from the box entry on (t in the ray's
  // parameter, sorted, an even number); returns the number of queries it took, 0 when the line
  // misses [tmin, tmax] inside the box.
  int crossings(const Ray& ray, std::vector<SurfaceHit>& hits) const;
  // One query along the line from its box entry `t_enter`, perturbed by `attempt` (0: not at
  // all). False when the hits are suspect: an odd count, or two of them at almost the same t.
  bool query(const Ray& ray, double t_enter, int attempt, std::vector<SurfaceHit>& hits) const;

  EmbreeScene scene_;
  Bounds3 bounds_;  // the mesh's own bounds
  Bounds3 padded_;  // bounds_ grown so that its surface lies strictly outside the mesh
  float diagonal_;  // length of bounds_' diagonal
};

}  // namespace caligo
