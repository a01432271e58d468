#include "guiding/guiding_field.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace caligo {

GuidingField::GuidingField(Bounds3 bounds, GuidingConfig config) : config_(config) {
  if (bounds.empty()) bounds = {Vec3(-1.0f), Vec3(1.0f)};
  const Vec3 margin = bounds.diagonal() * 0.01f + Vec3(1e-3f);
  bounds_ = {bounds.lo - margin, bounds.hi + margin};
  const Vec3 d = bounds_.diagonal();
  inverse_extent_ = {1.0f / d.x, 1.0f / d.y, 1.0f / d.z};
  nodes_.push_back({});
  trees_.emplace_back();
}

uint32_t GuidingField::leaf_of(Vec3 x) const {
  float p[3] = {std::clamp((x.x - bounds_.lo.x) * inverse_extent_.x, 0.0f, 1.0f),
                std::clamp((x.y - bounds_.lo.y) * inverse_extent_.y, 0.0f, 1.0f),
                std::clamp((x.z - bounds_.lo.z) * inverse_extent_.z, 0.0f, 1.0f)};
  uint32_t n = 0;
  while (nodes_[n].child != 0) {
    const SpatialNode& node = nodes_[n];
    float& c = p[node.axis];
    const uint32_t side = c >= 0.5f ? 1u : 0u;
    c = 2.0f * c - float(side);
    n = node.child + side;
  }
  return nodes_[n].tree;
}

const DirectionalTree* GuidingField::at(Vec3 x) const {
  const DirectionalTree& t = trees_[leaf_of(x)];
  return t.usable() ? &t : nullptr;
}

float GuidingField::fluence(Vec3 x, Bounds3* leaf) const {
  float p[3] = {std::clamp((x.x - bounds_.lo.x) * inverse_extent_.x, 0.0f, 1.0f),
                std::clamp((x.y - bounds_.lo.y) * inverse_extent_.y, 0.0f, 1.0f),
                std::clamp((x.z - bounds_.lo.z) * inverse_extent_.z, 0.0f, 1.0f)};
  float lo[3] = {0.0f, 0.0f, 0.0f}, size[3] = {1.0f, 1.0f, 1.0f};
  uint32_t n = 0;
  while (nodes_[n].child != 0) {
    const SpatialNode& node = nodes_[n];
    const int a = node.axis;
    const uint32_t side = p[a] >= 0.5f ? 1u : 0u;  // the same descent as leaf_of
    p[a] = 2.0f * p[a] - float(side);
    size[a] *= 0.5f;
    lo[a] += float(side) * size[a];
    n = node.child + side;
  }
  const Vec3 d = bounds_.diagonal();
  leaf->lo = bounds_.lo + Vec3(lo[0] * d.x, lo[1] * d.y, lo[2] * d.z);
  leaf->hi = leaf->lo + Vec3(size[0] * d.x, size[1] * d.y, size[2] * d.z);
  return trees_[nodes_[n].tree].fluence();
}

void GuidingField::record(Vec3 x, Vec3 w, double value) const { trees_[leaf_of(x)].record(w, value); }
void GuidingField::record(Vec3 x, const GuidingRecord& r) const { trees_[leaf_of(x)].record(r); }

size_t GuidingField::directional_nodes() const {
  size_t n = 0;
  for (const DirectionalTree& t : trees_) n += t.node_count();
  return n;
}

uint64_t GuidingField::memory_bytes() const {
  uint64_t bytes = nodes_.size() * sizeof(SpatialNode) + trees_.size() * sizeof(DirectionalTree);
  for (const DirectionalTree& t : trees_) bytes += t.memory_bytes();
  return bytes;
}

// Splits every leaf whose share of this iteration's vertices is above `threshold` (its children
// count half each, and split again while above it); both children start from the parent's tree,
// statistics included, which refinement then turns into each one's distribution.
void GuidingField::split_leaves(double threshold) {
  std::vector<double> count(nodes_.size());
  for (size_t n = 0; n < nodes_.size(); ++n)
    if (nodes_[n].child == 0) count[n] = trees_[nodes_[n].tree].vertex_count();
  uint64_t bytes = memory_bytes();
  for (size_t n = 0; n < nodes_.size(); ++n) {
    if (nodes_[n].child != 0 || !(count[n] > threshold)) continue;
    const DirectionalTree& parent = trees_[nodes_[n].tree];
    const uint64_t cost = 2 * sizeof(SpatialNode) + sizeof(DirectionalTree) + parent.memory_bytes();
    if (bytes + cost > config_.max_bytes) continue;  // the bound: this leaf stays as it is
    bytes += cost;
    const uint8_t axis = uint8_t((nodes_[n].axis + 1) % 3);
    const uint32_t first = uint32_t(nodes_.size()), old_tree = nodes_[n].tree;
    trees_.push_back(parent);
    nodes_.push_back({0, old_tree, axis});
    nodes_.push_back({0, uint32_t(trees_.size() - 1), axis});
    nodes_[n].child = first;
    count.push_back(count[n] * 0.5);
    count.push_back(count[n] * 0.5);
  }
}

void GuidingField::finish_iteration() {
  if (!training()) return;
  split_leaves(config_.spatial_threshold * std::sqrt(std::ldexp(1.0, completed_)));
  // Refined trees may grow; past the memory bound they are refined again, coarser, until they
  // fit (a split fraction above 1 splits nothing, so this ends).
  std::vector<DirectionalTree> next(trees_.size());
  for (double fraction = config_.split_fraction;; fraction *= 2.0) {
    uint64_t bytes = nodes_.size() * sizeof(SpatialNode);
    for (size_t i = 0; i < trees_.size(); ++i) {
      next[i] = trees_[i].refined(fraction, config_.max_depth);
      bytes += sizeof(DirectionalTree) + next[i].memory_bytes();
    }
    if (bytes <= config_.max_bytes || fraction > 1.0) break;
  }
  trees_ = std::move(next);
  ++completed_;
}

std::vector<uint64_t> GuidingField::statistics_words() const {
  std::vector<uint64_t> words;
  const auto put = [&](FixedTotal t) {
    words.push_back(t.lo & 0xffffffffu);
    words.push_back(t.lo >> 32);
    words.push_back(t.hi & 0xffffffffu);
    words.push_back(t.hi >> 32);
  };
  for (const DirectionalTree& t : trees_) {
    put(t.vertices().total());
    for (const AtomicFixedSum& s : t.moments()) put(s.total());
    for (const AtomicFixedSum& s : t.statistics()) put(s.total());
  }
  return words;
}

void GuidingField::set_statistics_words(const std::vector<uint64_t>& words) {
  size_t expected = 0;
  for (const DirectionalTree& t : trees_) expected += 4 * (1 + DirectionalTree::kMoments + t.statistics().size());
  if (words.size() != expected) throw std::invalid_argument("guiding statistics of another field's shape");
  size_t i = 0;
  const auto take = [&] {
    // Limbs summed over ranks may carry past 32 bits: recombined with carries, exactly.
    FixedTotal t;
    t += FixedTotal{words[i], 0};
    t += FixedTotal{words[i + 1] << 32, words[i + 1] >> 32};
    t += FixedTotal{0, words[i + 2]};
    t += FixedTotal{0, words[i + 3] << 32};
    i += 4;
    return t;
  };
  for (DirectionalTree& t : trees_) {
    const FixedTotal vertices = take();
    std::array<FixedTotal, DirectionalTree::kMoments> moments;
    for (FixedTotal& m : moments) m = take();
    std::vector<AtomicFixedSum> stats(t.statistics().size());
    for (AtomicFixedSum& s : stats) s.set(take());
    t = DirectionalTree::from_parts(t.nodes(), std::move(stats), vertices, {t.fraction(true), t.fraction(false)});
    t.set_moments(moments);
  }
}

}  // namespace caligo
