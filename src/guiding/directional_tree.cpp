#include "guiding/directional_tree.h"

#include <algorithm>
#include <cmath>

#include "core/math.h"

namespace caligo {

Vec2 sphere_to_square(Vec3 w) {
  const float z = std::clamp(w.z, -1.0f, 1.0f);
  float phi = std::atan2(w.y, w.x) * (0.5f / kPi);
  if (phi < 0.0f) phi += 1.0f;
  return {std::clamp((z + 1.0f) * 0.5f, 0.0f, 1.0f), std::clamp(phi, 0.0f, 1.0f)};
}

Vec3 square_to_sphere(Vec2 p) {
  const float z = 2.0f * p.x - 1.0f;
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  const float phi = 2.0f * kPi * p.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

DirectionalTree::DirectionalTree() : nodes_(1), stats_(4) {}

namespace {

// Picks the half [0, p) or [p, 1) that u falls in and rescales u to [0, 1) within it.
int choose(double& u, double p) {
  if (u < p) {
    u = p > 0.0 ? u / p : 0.0;
    return 0;
  }
  u = p < 1.0 ? (u - p) / (1.0 - p) : 0.0;
  return 1;
}

// The quadrant of p (x first: index = ix + 2 iy), and p rescaled into it.
int quadrant(double& x, double& y) {
  const int ix = x >= 0.5 ? 1 : 0, iy = y >= 0.5 ? 1 : 0;
  x = 2.0 * x - ix;
  y = 2.0 * y - iy;
  return ix + 2 * iy;
}

}  // namespace

Vec3 DirectionalTree::sample(Vec2 u, float* pdf) const {
  double ux = std::min(double(u.x), 0x1.fffffffffffffp-1), uy = std::min(double(u.y), 0x1.fffffffffffffp-1);
  double x0 = 0.0, y0 = 0.0, size = 1.0, density = 1.0;
  uint32_t n = 0;
  for (;;) {
    const Node& node = nodes_[n];
    const auto& e = node.energy;
    const double total = double(e[0]) + e[1] + e[2] + e[3];
    // Column (x) by the halves' energies, then row (y) within the column.
    const int ix = choose(ux, (double(e[0]) + e[2]) / total);
    const double column = double(e[ix]) + e[ix + 2];
    const int iy = choose(uy, column > 0.0 ? e[ix] / column : 1.0);
    const int i = ix + 2 * iy;
    density *= 4.0 * e[i] / total;
    size *= 0.5;
    x0 += ix * size;
    y0 += iy * size;
    if (node.child[i] == 0) break;
    n = node.child[i];
  }
  *pdf = float(density / (4.0 * kPi));
  return square_to_sphere({float(x0 + ux * size), float(y0 + uy * size)});
}

float DirectionalTree::pdf(Vec3 w) const {
  if (!usable()) return 0.0f;
  const Vec2 p = sphere_to_square(w);
  double x = p.x, y = p.y, density = 1.0;
  uint32_t n = 0;
  for (;;) {
    const Node& node = nodes_[n];
    const auto& e = node.energy;
    const int i = quadrant(x, y);
    density *= 4.0 * e[i] / (double(e[0]) + e[1] + e[2] + e[3]);
    if (node.child[i] == 0) break;
    n = node.child[i];
  }
  return float(density / (4.0 * kPi));
}

void DirectionalTree::record(Vec3 w, double value) const {
  vertices_.add(1.0);
  const Vec2 p = sphere_to_square(w);
  double x = p.x, y = p.y;
  uint32_t n = 0;
  for (;;) {
    const int i = quadrant(x, y);
    if (nodes_[n].child[i] == 0) {
      stats_[4 * n + i].add(value);
      return;
    }
    n = nodes_[n].child[i];
  }
}

namespace {

// Each quadrant's energy this iteration: its statistic when a leaf, its child's sum otherwise.
void gather(const std::vector<DirectionalTree::Node>& nodes, const std::vector<AtomicFixedSum>& stats, uint32_t n,
            std::vector<std::array<double, 4>>& totals) {
  for (int i = 0; i < 4; ++i) {
    const uint32_t c = nodes[n].child[i];
    if (c == 0) {
      totals[n][i] = stats[4 * n + i].value();
      continue;
    }
    gather(nodes, stats, c, totals);
    totals[n][i] = totals[c][0] + totals[c][1] + totals[c][2] + totals[c][3];
  }
}

struct Refiner {
  const std::vector<DirectionalTree::Node>& old;
  const std::vector<std::array<double, 4>>& totals;
  double threshold;  // energy above which a quadrant is split
  int max_depth;
  std::vector<DirectionalTree::Node> out;

  // A new node for old node `n` (or, n < 0, for an old leaf of energy `leaf` split evenly).
  uint32_t build(int n, double leaf, int depth) {
    const uint32_t index = uint32_t(out.size());
    out.emplace_back();
    for (int i = 0; i < 4; ++i) {
      const double e = n >= 0 ? totals[size_t(n)][i] : leaf * 0.25;
      out[index].energy[i] = float(e);
      if (depth < max_depth && e > threshold) {
        const uint32_t old_child = n >= 0 ? old[size_t(n)].child[i] : 0;
        const uint32_t child = build(old_child ? int(old_child) : -1, e, depth + 1);
        out[index].child[i] = child;
      }
    }
    return index;
  }
};

}  // namespace

DirectionalTree DirectionalTree::refined(double split_fraction, int max_depth) const {
  std::vector<std::array<double, 4>> totals(nodes_.size());
  gather(nodes_, stats_, 0, totals);
  const double total = totals[0][0] + totals[0][1] + totals[0][2] + totals[0][3];
  DirectionalTree next;
  if (!(total > 0.0)) {  // nothing learnt here this iteration: keep what was known
    next.nodes_ = nodes_;
    next.stats_.assign(stats_.size(), AtomicFixedSum());
    next.total_ = total_;
    return next;
  }
  Refiner r{nodes_, totals, split_fraction * total, max_depth, {}};
  r.build(0, 0.0, 1);
  next.nodes_ = std::move(r.out);
  next.stats_.assign(4 * next.nodes_.size(), AtomicFixedSum());
  const auto& e = next.nodes_[0].energy;
  next.total_ = e[0] + e[1] + e[2] + e[3];
  return next;
}

DirectionalTree DirectionalTree::from_parts(std::vector<Node> nodes, std::vector<AtomicFixedSum> stats,
                                            FixedTotal vertices) {
  DirectionalTree t;
  t.nodes_ = std::move(nodes);
  t.stats_ = std::move(stats);
  t.vertices_.set(vertices);
  const auto& e = t.nodes_[0].energy;
  t.total_ = e[0] + e[1] + e[2] + e[3];
  return t;
}

void DirectionalTree::add_statistics(const DirectionalTree& other) {
  for (size_t i = 0; i < stats_.size(); ++i) {
    FixedTotal t = stats_[i].total();
    t += other.stats_[i].total();
    stats_[i].set(t);
  }
  FixedTotal v = vertices_.total();
  v += other.vertices_.total();
  vertices_.set(v);
}

}  // namespace caligo
