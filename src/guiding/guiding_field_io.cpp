// GuidingField's bytes (checkpoints carry them inside the film: Film::training_state). Little-
// endian raw values; a reader that checks every count against what is left, every index against
// what it indexes and every value against what training can produce, since a checkpoint is
// untrusted input.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/error.h"
#include "guiding/guiding_field.h"

namespace caligo {
namespace {

constexpr char kMagic[8] = {'C', 'G', 'F', 'I', 'E', 'L', 'D', '1'};
constexpr uint32_t kMaxNodes = 1u << 26;
constexpr int kMaxDepth = 30, kMaxIterations = 30;

class Writer {
 public:
  template <typename T>
  void put(const T& v) {
    bytes.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  std::string bytes;
};

class Reader {
 public:
  Reader(std::string_view bytes, const std::string& source) : bytes_(bytes), where_{source, ""} {}
  template <typename T>
  T get() {
    T v;
    if (bytes_.size() - offset_ < sizeof v) fail("truncated");
    std::memcpy(&v, bytes_.data() + offset_, sizeof v);
    offset_ += sizeof v;
    return v;
  }
  // A count of items of `item_bytes` each, which must fit in what is left.
  uint32_t count(size_t item_bytes, uint32_t limit) {
    const uint32_t n = get<uint32_t>();
    if (n > limit || uint64_t(n) * item_bytes > bytes_.size() - offset_) fail("a count larger than the data");
    return n;
  }
  bool done() const { return offset_ == bytes_.size(); }
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(where_, "guiding field: " + what + " (corrupt)");
  }

 private:
  std::string_view bytes_;
  size_t offset_ = 0;
  SourceLocation where_;
};

void put_total(Writer& w, FixedTotal t) {
  w.put(t.lo);
  w.put(t.hi);
}

FixedTotal get_total(Reader& r) {
  const uint64_t lo = r.get<uint64_t>(), hi = r.get<uint64_t>();
  return {lo, hi};
}

bool finite_non_negative(float v) { return std::isfinite(v) && v >= 0.0f; }

// Children after their parent (so descents end), energies that sampling can divide by, and no
// leaf deeper than the config allows.
DirectionalTree read_tree(Reader& r, int max_depth) {
  constexpr size_t kNodeBytes = sizeof(DirectionalTree::Node) + 4 * 2 * sizeof(uint64_t);
  const uint32_t n = r.count(kNodeBytes, kMaxNodes);
  if (n == 0) r.fail("a directional tree without nodes");
  std::vector<DirectionalTree::Node> nodes(n);
  std::vector<int> depth(n, 0);
  depth[0] = 1;
  for (uint32_t i = 0; i < n; ++i) {
    for (auto& c : nodes[i].child) c = r.get<uint32_t>();
    for (auto& e : nodes[i].energy) e = r.get<float>();
  }
  for (uint32_t i = 0; i < n; ++i) {
    for (int q = 0; q < 4; ++q) {
      if (!finite_non_negative(nodes[i].energy[q])) r.fail("a negative or non-finite energy");
      const uint32_t c = nodes[i].child[q];
      if (c == 0) continue;
      if (c <= i || c >= n || depth[c] != 0) r.fail("a directional child index out of order");
      depth[c] = depth[i] + 1;
      if (depth[c] > max_depth) r.fail("a directional tree deeper than its limit");
      const auto& e = nodes[c].energy;
      if (nodes[i].energy[q] > 0.0f && !(e[0] + e[1] + e[2] + e[3] > 0.0f)) r.fail("an inconsistent energy");
    }
    if (i > 0 && depth[i] == 0) r.fail("a directional node nobody points to");
  }
  std::vector<AtomicFixedSum> stats(4 * size_t(n));
  for (AtomicFixedSum& s : stats) s.set(get_total(r));
  const FixedTotal vertices = get_total(r);
  std::array<FixedTotal, DirectionalTree::kMoments> moments;
  for (FixedTotal& m : moments) m = get_total(r);
  std::array<float, 2> fractions;
  for (float& f : fractions) {
    f = r.get<float>();
    if (std::find(DirectionalTree::kFractions.begin(), DirectionalTree::kFractions.end(), f) ==
        DirectionalTree::kFractions.end())
      r.fail("a guided share that is not one of the candidates");
  }
  DirectionalTree tree = DirectionalTree::from_parts(std::move(nodes), std::move(stats), vertices, fractions);
  tree.set_moments(moments);
  return tree;
}

}  // namespace

std::string GuidingField::to_bytes() const {
  Writer w;
  w.bytes.append(kMagic, sizeof kMagic);
  w.put(int32_t(config_.iterations));
  w.put(config_.spatial_threshold);
  w.put(config_.split_fraction);
  w.put(int32_t(config_.max_depth));
  w.put(config_.max_bytes);
  for (float v : {bounds_.lo.x, bounds_.lo.y, bounds_.lo.z, bounds_.hi.x, bounds_.hi.y, bounds_.hi.z}) w.put(v);
  w.put(int32_t(completed_));
  w.put(uint32_t(nodes_.size()));
  for (const SpatialNode& n : nodes_) {
    w.put(n.child);
    w.put(n.tree);
    w.put(uint32_t(n.axis));
  }
  w.put(uint32_t(trees_.size()));
  for (const DirectionalTree& t : trees_) {
    w.put(uint32_t(t.node_count()));
    for (const DirectionalTree::Node& n : t.nodes()) {
      for (uint32_t c : n.child) w.put(c);
      for (float e : n.energy) w.put(e);
    }
    for (const AtomicFixedSum& s : t.statistics()) put_total(w, s.total());
    put_total(w, t.vertices().total());
    for (const AtomicFixedSum& m : t.moments()) put_total(w, m.total());
    w.put(t.fraction(true));
    w.put(t.fraction(false));
  }
  return std::move(w.bytes);
}

GuidingField GuidingField::from_bytes(std::string_view bytes, const std::string& source) {
  Reader r(bytes, source);
  char magic[sizeof kMagic];
  for (char& c : magic) c = r.get<char>();
  if (std::memcmp(magic, kMagic, sizeof kMagic) != 0) r.fail("not a guiding field");
  GuidingField f;
  GuidingConfig& c = f.config_;
  c.iterations = r.get<int32_t>();
  c.spatial_threshold = r.get<double>();
  c.split_fraction = r.get<double>();
  c.max_depth = r.get<int32_t>();
  c.max_bytes = r.get<uint64_t>();
  if (c.iterations < 0 || c.iterations > kMaxIterations || !(c.spatial_threshold > 0.0) ||
      !std::isfinite(c.spatial_threshold) || !(c.split_fraction > 0.0 && c.split_fraction <= 1.0) ||
      c.max_depth < 1 || c.max_depth > kMaxDepth)
    r.fail("settings out of range");
  float b[6];
  for (float& v : b) v = r.get<float>();
  f.bounds_ = {{b[0], b[1], b[2]}, {b[3], b[4], b[5]}};
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(b[a]) || !std::isfinite(b[a + 3]) || !(b[a] < b[a + 3])) r.fail("bounds out of range");
  const Vec3 d = f.bounds_.diagonal();
  f.inverse_extent_ = {1.0f / d.x, 1.0f / d.y, 1.0f / d.z};
  f.completed_ = r.get<int32_t>();
  if (f.completed_ < 0 || f.completed_ > c.iterations) r.fail("an iteration count out of range");
  const uint32_t nodes = r.count(3 * sizeof(uint32_t), kMaxNodes);
  if (nodes == 0) r.fail("no spatial nodes");
  f.nodes_.resize(nodes);
  for (SpatialNode& n : f.nodes_) {
    n.child = r.get<uint32_t>();
    n.tree = r.get<uint32_t>();
    const uint32_t axis = r.get<uint32_t>();
    if (axis > 2) r.fail("a split axis out of range");
    n.axis = uint8_t(axis);
  }
  const uint32_t trees = r.count(sizeof(uint32_t), kMaxNodes);
  std::vector<bool> used(trees, false), reached(nodes, false);
  for (uint32_t i = 0; i < nodes; ++i) {
    const SpatialNode& n = f.nodes_[i];
    if (i > 0 && !reached[i]) r.fail("a spatial node nobody points to");
    if (n.child == 0) {
      if (n.tree >= trees || used[n.tree]) r.fail("a leaf's tree index out of range");
      used[n.tree] = true;
      continue;
    }
    if (n.child <= i || uint64_t(n.child) + 1 >= nodes || reached[n.child] || reached[n.child + 1])
      r.fail("a spatial child index out of order");
    reached[n.child] = reached[n.child + 1] = true;
  }
  for (bool u : used)
    if (!u) r.fail("a directional tree no leaf holds");
  f.trees_.reserve(trees);
  for (uint32_t i = 0; i < trees; ++i) f.trees_.push_back(read_tree(r, c.max_depth));
  if (!r.done()) r.fail("bytes after its end");
  return f;
}

}  // namespace caligo
