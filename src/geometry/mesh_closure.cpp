#include "geometry/mesh_closure.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <map>
#include <vector>

namespace caligo {
namespace {

// Vertex ids after welding equal positions (-0 and +0 are one position).
std::vector<uint32_t> welded_ids(const TriangleMesh& mesh) {
  std::map<std::array<uint32_t, 3>, uint32_t> first_with;
  std::vector<uint32_t> id(mesh.positions.size());
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    const Vec3 p = mesh.positions[v] + Vec3(0.0f);
    const std::array<uint32_t, 3> key = {std::bit_cast<uint32_t>(p.x), std::bit_cast<uint32_t>(p.y),
                                         std::bit_cast<uint32_t>(p.z)};
    id[v] = first_with.try_emplace(key, uint32_t(v)).first->second;
  }
  return id;
}

// One directed use of an undirected edge: the key orders the endpoints, `forward` says whether
// the triangle traverses it from the smaller id to the larger.
struct EdgeUse {
  uint64_t key;
  bool forward;
  bool operator<(const EdgeUse& o) const { return key < o.key; }
};

}  // namespace

MeshClosure check_closure(const TriangleMesh& mesh) {
  const std::vector<uint32_t> id = welded_ids(mesh);
  std::vector<EdgeUse> uses;
  uses.reserve(mesh.indices.size());
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    const std::array<uint32_t, 3> v = {id[mesh.indices[3 * t]], id[mesh.indices[3 * t + 1]],
                                       id[mesh.indices[3 * t + 2]]};
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) continue;
    for (size_t k = 0; k < 3; ++k) {
      const uint32_t a = v[k], b = v[(k + 1) % 3];
      uses.push_back({uint64_t(std::min(a, b)) << 32 | std::max(a, b), a < b});
    }
  }
  std::sort(uses.begin(), uses.end());
  MeshClosure result;
  for (size_t i = 0; i < uses.size();) {
    size_t j = i;
    while (j < uses.size() && uses[j].key == uses[i].key) ++j;
    if (j - i == 1)
      ++result.boundary_edges;
    else if (j - i > 2)
      ++result.non_manifold_edges;
    else if (uses[i].forward == uses[i + 1].forward)
      ++result.misoriented_edges;
    i = j;
  }
  return result;
}

}  // namespace caligo
