// Whether a triangle mesh is a closed, consistently oriented surface: the test a surface must
// pass to bound a medium (media/medium_stack.h). Vertices are welded by exact position first
// (loaders split vertices at UV and normal seams). Each undirected edge is then
//   boundary      used by one triangle (an open mesh);
//   non-manifold  used by three or more;
//   misoriented   used by two triangles that traverse it in the same direction;
// and the mesh is closed when there are none of these. Triangles that collapse when welded
// (two corners at one position) are ignored: they bound nothing.
//
// Thread safety: a pure function.
#pragma once

#include <cstddef>

#include "geometry/triangle_mesh.h"

namespace caligo {

struct MeshClosure {
  size_t boundary_edges = 0;
  size_t non_manifold_edges = 0;
  size_t misoriented_edges = 0;

  bool closed() const { return boundary_edges == 0 && non_manifold_edges == 0 && misoriented_edges == 0; }
};

// `mesh` must have passed validate_mesh() (indices in range).
MeshClosure check_closure(const TriangleMesh& mesh);

}  // namespace caligo
