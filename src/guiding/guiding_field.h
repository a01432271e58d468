// Path guiding's learnt field of incident radiance, as an SD-tree (Mueller et al. 2017,
// "Practical Path Guiding"; docs/techniques.md says why this and not a mixture model): a binary
// tree over the scene's bounds, split in the middle along x, y, z in turn, whose leaves each hold
// a DirectionalTree of the radiance arriving there from every direction of the sphere. Surface
// and medium vertices share it (both see the same incident radiance; the path tracer mixes the
// guided density with the BSDF's or the phase function's).
//
// Training is in iterations of doubling sample counts (guiding_schedule.h). During one, every
// guided vertex records the radiance its path brought back along the sampled direction, divided
// by that direction's pdf, into the leaf it lies in; after it, finish_iteration() splits every
// spatial leaf that recorded more than c sqrt(2^k) vertices and rebuilds every directional tree
// from its statistics. The sums are exact integers (atomic_fixed_sum.h), so the field after an
// iteration is the same bit for bit for any thread count, pass split, resume or MPI rank count.
// Memory is bounded (GuidingConfig::max_bytes): past it, spatial leaves are no longer split.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/bounds.h"
#include "guiding/directional_tree.h"

namespace caligo {

struct GuidingConfig {
  int iterations = 7;                // training iterations: samples 0 .. 2^7 - 2 train, later ones use the last field
  double spatial_threshold = 12000;  // c: a leaf splits past c sqrt(2^k) vertices in iteration k (Mueller's value)
  double split_fraction = 0.01;      // rho: a directional quadrant splits past this share of its tree's energy
  int max_depth = 20;                // of the directional trees
  uint64_t max_bytes = uint64_t(256) << 20;
  friend bool operator==(const GuidingConfig&, const GuidingConfig&) = default;
};

class GuidingField {
 public:
  struct SpatialNode {
    uint32_t child = 0;  // 0: a leaf; else the first of two children (the second is child + 1)
    uint32_t tree = 0;   // a leaf's DirectionalTree
    uint8_t axis = 0;    // the axis this node splits (0 x, 1 y, 2 z), in the middle
  };

  // A field of one leaf and no knowledge over `bounds` (the scene's), which is made a little
  // larger so that vertices on its faces are inside.
  explicit GuidingField(Bounds3 bounds, GuidingConfig config = {});

  // The directional distribution at x (points outside the bounds are clamped in), or null where
  // nothing has been learnt yet (the path tracer then samples the BSDF or phase function alone).
  const DirectionalTree* at(Vec3 x) const;
  // DirectionalTree::fluence of the leaf at x (0 where nothing was learnt), and the leaf's box in
  // world space (so that a caller walking a ray can skip the lookups of points inside it).
  float fluence(Vec3 x, Bounds3* leaf) const;
  // Training: see DirectionalTree::record. From any number of threads at once.
  void record(Vec3 x, Vec3 w, double value) const;
  void record(Vec3 x, const GuidingRecord& r) const;

  int completed_iterations() const { return completed_; }
  bool training() const { return completed_ < config_.iterations; }
  // Ends the current training iteration: splits, refines, zeroes the statistics.
  void finish_iteration();

  const GuidingConfig& config() const { return config_; }
  const Bounds3& bounds() const { return bounds_; }
  size_t spatial_leaves() const { return trees_.size(); }
  const DirectionalTree& tree(size_t leaf) const { return trees_[leaf]; }
  size_t directional_nodes() const;
  uint64_t memory_bytes() const;

  // The whole field, training statistics included, for checkpoints (guiding_field_io.cpp).
  // from_bytes checks every index and value and throws InputError naming `source` for bytes
  // that are not such a field.
  std::string to_bytes() const;
  static GuidingField from_bytes(std::string_view bytes, const std::string& source);

  // The training statistics alone, as 32-bit limbs in 64-bit words (so that MPI_SUM over ranks is
  // exact), and setting them from such words (summed over the ranks' fields, which have the same
  // structure). set_statistics_words throws std::invalid_argument for words of another shape.
  std::vector<uint64_t> statistics_words() const;
  void set_statistics_words(const std::vector<uint64_t>& words);

  friend bool operator==(const GuidingField& a, const GuidingField& b) { return a.to_bytes() == b.to_bytes(); }

 private:
  GuidingField() = default;
  uint32_t leaf_of(Vec3 x) const;
  void split_leaves(double threshold);

  GuidingConfig config_;
  Bounds3 bounds_;
  Vec3 inverse_extent_;
  int completed_ = 0;
  std::vector<SpatialNode> nodes_;
  std::vector<DirectionalTree> trees_;
};

}  // namespace caligo
