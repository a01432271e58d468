// Edge adjacency of an occluder mesh, built once per mesh, and its silhouette seen from a
// point light (Wyman & Ramsey 2008, section 4: shadow volumes from silhouette edges).
//
// Vertices are welded by exact position (loaders duplicate vertices at UV seams and hard
// normals; the shadow volume needs the topology, not the shading). Each undirected edge is
// classified:
//   manifold   two triangles, traversing it in opposite directions (a closed, consistently
//              oriented surface): the only kind a silhouette can be made of;
//   boundary   one triangle (an open mesh);
//   non-manifold three or more triangles;
//   misoriented two triangles traversing it in the same direction (inconsistent winding).
// closed() is true when every edge is manifold. Shadow volumes are built only from closed
// meshes: an open or non-manifold occluder would give a volume with holes, so the caller
// leaves it to the shadow map alone (with a warning naming problem()). We do not extrude
// boundary edges as "always silhouette", because that is correct only for one-sided
// occluders and gives a silently wrong volume for the two-sided sheets scenes use.
//
// Thread safety: const after construction.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/vec.h"
#include "geometry/triangle_mesh.h"

namespace caligo {

// A manifold edge: tri[0] traverses it v[0] -> v[1], tri[1] traverses it v[1] -> v[0].
struct MeshEdge {
  uint32_t v[2];
  uint32_t tri[2];
};

class MeshEdges {
 public:
  // World-space mesh; indices must be in range (validate_mesh()). Triangles that collapse
  // when welded (two corners at one position) are dropped: they bound nothing.
  explicit MeshEdges(const TriangleMesh& mesh);

  const std::vector<Vec3>& vertices() const { return vertices_; }  // welded
  const std::vector<std::array<uint32_t, 3>>& triangles() const { return triangles_; }
  const std::vector<MeshEdge>& edges() const { return edges_; }  // the manifold edges only

  size_t boundary_edge_count() const { return boundary_; }
  size_t non_manifold_edge_count() const { return non_manifold_; }
  size_t misoriented_edge_count() const { return misoriented_; }
  size_t dropped_triangle_count() const { return dropped_; }
  bool closed() const {
    return boundary_ == 0 && non_manifold_ == 0 && misoriented_ == 0 && !triangles_.empty();
  }
  // Empty when closed(); otherwise the counts and the first offending edge with its
  // endpoints, e.g. "12 boundary edges (open mesh), first from (0, 1, 0) to (1, 1, 0)".
  const std::string& problem() const { return problem_; }

 private:
  // problem_ from the counts and the first offending edge of each kind.
  void describe_problems(const std::string& first_boundary, const std::string& first_non_manifold,
                         const std::string& first_misoriented);
  std::vector<Vec3> vertices_;
  std::vector<std::array<uint32_t, 3>> triangles_;
  std::vector<MeshEdge> edges_;
  size_t boundary_ = 0, non_manifold_ = 0, misoriented_ = 0, dropped_ = 0;
  std::string problem_;
};

// The silhouette of a closed mesh seen from a point light at `light`.
struct Silhouette {
  // Per triangle of MeshEdges::triangles(): 1 when it faces the light, dot(n, light - p) > 0
  // with n = (p1 - p0) x (p2 - p0) evaluated in double. A triangle whose plane contains the
  // light counts as facing away, consistently, so the lit set's boundary stays closed.
  std::vector<uint8_t> lit;
  // Silhouette edges (manifold edges with one lit and one unlit triangle) as welded vertex
  // pairs, in the direction the LIT triangle traverses them. The silhouette is then a set
  // of closed loops (every vertex has as many outgoing as incoming edges), and the quad
  // (b, a, a', b') extruded from (a, b) is wound outwards.
  std::vector<std::array<uint32_t, 2>> edges;
  size_t lit_count = 0;
};

bool faces_light(Vec3 p0, Vec3 p1, Vec3 p2, Vec3 light);
Silhouette find_silhouette(const MeshEdges& mesh, Vec3 light);

}  // namespace caligo
