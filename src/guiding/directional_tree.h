// The directional half of an SD-tree (Mueller et al. 2017, "Practical Path Guiding"): a quadtree
// over the unit square, which the cylindrical map (z = cos theta, phi) lays over the sphere of
// directions without distorting area, so that a density on the square is the same density on
// the sphere over 4 pi. Each node holds the energy of its four quadrants; sampling descends by
// those energies (hierarchical warping: the random numbers are rescaled at each level, so their
// stratification carries over), and the density of a leaf is the product of 4 e_i / sum e over
// the levels above it.
// Beside the distribution, each quadrant of the same structure gathers this iteration's
// training statistics (radiance over the pdf of the sampled direction), in exact atomic sums
// (atomic_fixed_sum.h); refined() turns them into the next iteration's tree.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/vec.h"
#include "guiding/atomic_fixed_sum.h"

namespace caligo {

// The area-preserving map between the sphere and the unit square: x = (cos theta + 1) / 2,
// y = phi / 2 pi.
Vec2 sphere_to_square(Vec3 w);
Vec3 square_to_sphere(Vec2 p);

class DirectionalTree {
 public:
  struct Node {
    std::array<uint32_t, 4> child{};  // 0: the quadrant is a leaf (node 0 is the root, nobody's child)
    std::array<float, 4> energy{};
  };

  DirectionalTree();  // one node without energy: not usable until trained

  // Whether the tree holds a distribution (some energy); a tree that is not must not be sampled.
  bool usable() const { return total_ > 0.0f; }
  // A direction and its solid-angle density, from two uniform numbers in [0, 1).
  Vec3 sample(Vec2 u, float* pdf) const;
  float pdf(Vec3 w) const;

  // Training, from any number of threads at once: `value` into the leaf holding w, and one vertex
  // into the count the spatial tree splits by. (const: the statistics sit beside the distribution,
  // which does not change while they gather.)
  void record(Vec3 w, double value) const;
  double vertex_count() const { return vertices_.value(); }

  // The next iteration's tree: this iteration's statistics as the energies, a quadrant split while
  // it holds more than `split_fraction` of the total and is above `max_depth`, and merged when it
  // holds less; statistics zero. Without statistics (no vertex recorded energy here) the
  // distribution stays as it is.
  DirectionalTree refined(double split_fraction, int max_depth) const;

  size_t node_count() const { return nodes_.size(); }
  size_t memory_bytes() const { return nodes_.size() * (sizeof(Node) + 4 * sizeof(AtomicFixedSum)); }
  const std::vector<Node>& nodes() const { return nodes_; }

  // For guiding_field_io.cpp: the raw parts, and a tree from them (checked by the caller).
  const std::vector<AtomicFixedSum>& statistics() const { return stats_; }
  const AtomicFixedSum& vertices() const { return vertices_; }
  static DirectionalTree from_parts(std::vector<Node> nodes, std::vector<AtomicFixedSum> stats, FixedTotal vertices);
  // Adds another tree's statistics (same structure: the same field on another MPI rank).
  void add_statistics(const DirectionalTree& other);

 private:
  std::vector<Node> nodes_;
  mutable std::vector<AtomicFixedSum> stats_;  // 4 per node, in quadrant order
  mutable AtomicFixedSum vertices_;
  float total_ = 0.0f;  // the root's energy
};

}  // namespace caligo
