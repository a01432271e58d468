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

void DirectionalTree::record(const GuidingRecord& r) const {
  if (r.pdf_used > 0.0f) record(r.wi, r.radiance / r.pdf_used);
  if (!usable() || !(r.pdf_used > 0.0f)) return;
  // E[(f L)^2 / (p_k p_used)] over samples drawn from p_used is candidate k's second moment.
  // Scaled by 2^16 so that dim scenes keep resolution in the fixed-point sums.
  const double fl = double(r.f) * r.radiance, guide = pdf(r.wi);
  if (!(fl > 0.0)) return;
  const size_t base = r.surface ? 0 : kFractions.size();
  for (size_t k = 0; k < kFractions.size(); ++k) {
    const double p = kFractions[k] * guide + (1.0 - kFractions[k]) * r.pdf_native;
    moments_[base + k].add(p > 0.0 ? 0x1p16 * fl * fl / (p * r.pdf_used) : 0x1p100);
  }
}

namespace {

// The candidate share of least second moment; `current` without data.
float best_fraction(const std::array<AtomicFixedSum, DirectionalTree::kMoments>& moments, size_t base, float current) {
  double best = 0.0;
  float chosen = current;
  for (size_t k = 0; k < DirectionalTree::kFractions.size(); ++k) {
    const double m = moments[base + k].value();
    if (!(m > 0.0)) return current;  // no vertex of this kind recorded here
    if (k == 0 || m < best) {
      best = m;
      chosen = DirectionalTree::kFractions[k];
    }
  }
  return chosen;
}

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
  double scale;      // energy stored per unit of statistic (1 / the iteration's vertex count)
  int max_depth;
  std::vector<DirectionalTree::Node> out;

  // A new node for old node `n` (or, n < 0, for an old leaf of energy `leaf` split evenly).
  uint32_t build(int n, double leaf, int depth) {
    const uint32_t index = uint32_t(out.size());
    out.emplace_back();
    for (int i = 0; i < 4; ++i) {
      const double e = n >= 0 ? totals[size_t(n)][i] : leaf * 0.25;
      out[index].energy[i] = float(e * scale);
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
  next.fraction_ = {best_fraction(moments_, 0, fraction_[0]),
                    best_fraction(moments_, kFractions.size(), fraction_[1])};
  if (!(total > 0.0)) {  // nothing learnt here this iteration: keep what was known
    next.nodes_ = nodes_;
    next.stats_.assign(stats_.size(), AtomicFixedSum());
    next.total_ = total_;
    return next;
  }
  const double vertices = vertices_.value();
  Refiner r{nodes_, totals, split_fraction * total, vertices > 0.0 ? 1.0 / vertices : 1.0, max_depth, {}};
  r.build(0, 0.0, 1);
  next.nodes_ = std::move(r.out);
  next.stats_.assign(4 * next.nodes_.size(), AtomicFixedSum());
  const auto& e = next.nodes_[0].energy;
  next.total_ = e[0] + e[1] + e[2] + e[3];
  return next;
}

DirectionalTree DirectionalTree::from_parts(std::vector<Node> nodes, std::vector<AtomicFixedSum> stats,
                                            FixedTotal vertices, std::array<float, 2> fractions) {
  DirectionalTree t;
  t.fraction_ = fractions;
  t.nodes_ = std::move(nodes);
  t.stats_ = std::move(stats);
  t.vertices_.set(vertices);
  const auto& e = t.nodes_[0].energy;
  t.total_ = e[0] + e[1] + e[2] + e[3];
  return t;
}


}  // namespace caligo
