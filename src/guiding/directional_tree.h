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

// What training learns from one guided vertex: the direction, the radiance that came back along
// it, the scattering function's value there (BSDF times cosine, or phase function; channel
// averages), and the densities of the native (BSDF or phase) sampling and of the mixture that
// drew it.
struct GuidingRecord {
  Vec3 wi;
  double radiance;
  float f, pdf_native, pdf_used;
  bool surface;
};

class DirectionalTree {
 public:
  // The guided density's shares of the one-sample mixture a tree may choose between; after each
  // iteration it keeps, for surface and for medium vertices apart, the one whose estimated second
  // moment of f L / p was least (a discrete form of Mueller 2019's learnt BSDF-sampling fraction):
  // where guiding does not pay (a forward-scattering, dense cloud) the share falls to 0.
  static constexpr std::array<float, 5> kFractions{0.0f, 0.125f, 0.25f, 0.5f, 0.75f};

  struct Node {
    std::array<uint32_t, 4> child{};  // 0: the quadrant is a leaf (node 0 is the root, nobody's child)
    std::array<float, 4> energy{};
  };

  DirectionalTree();  // one node without energy: not usable until trained

  // Whether the tree holds a distribution (some energy); a tree that is not must not be sampled.
  bool usable() const { return total_ > 0.0f; }
  // The radiance integrated over all directions (the fluence) that the last iteration's vertices
  // here saw, on average: refinement divides the energies by the vertex count, so the root's
  // energy is Mueller's estimate of the integral per vertex (sampling uses only ratios).
  float fluence() const { return total_; }
  // A direction and its solid-angle density, from two uniform numbers in [0, 1).
  Vec3 sample(Vec2 u, float* pdf) const;
  float pdf(Vec3 w) const;

  // Training, from any number of threads at once: `value` into the leaf holding w, and one vertex
  // into the count the spatial tree splits by. (const: the statistics sit beside the distribution,
  // which does not change while they gather.)
  void record(Vec3 w, double value) const;
  // record(), and the second moments of every candidate share.
  void record(const GuidingRecord& r) const;
  // The guided density's share at surface or medium vertices.
  float fraction(bool surface) const { return fraction_[surface ? 0 : 1]; }
  void set_fractions(float surface, float volume) { fraction_ = {surface, volume}; }
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
  static constexpr size_t kMoments = 2 * kFractions.size();  // surface candidates, then medium ones
  const std::array<AtomicFixedSum, kMoments>& moments() const { return moments_; }
  void set_moments(const std::array<FixedTotal, kMoments>& m) {
    for (size_t i = 0; i < kMoments; ++i) moments_[i].set(m[i]);
  }
  static DirectionalTree from_parts(std::vector<Node> nodes, std::vector<AtomicFixedSum> stats, FixedTotal vertices,
                                    std::array<float, 2> fractions);

 private:
  std::vector<Node> nodes_;
  mutable std::vector<AtomicFixedSum> stats_;  // 4 per node, in quadrant order
  mutable AtomicFixedSum vertices_;
  mutable std::array<AtomicFixedSum, kMoments> moments_;
  float total_ = 0.0f;  // the root's energy
  // Surface, medium. A new tree's share is 0: the first field comes from one sample per pixel, and a
  // fixed 1/2 on it made `sss` 3x noisier per sample; its iteration still estimates every
  // candidate's second moment (from the native samples), so the next iteration picks a share.
  std::array<float, 2> fraction_{0.0f, 0.0f};
};

}  // namespace caligo
