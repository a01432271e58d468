#include "lights/light_tree.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace caligo {
namespace {

// The cosine factors of the importance are floored here wherever the cone test passes, so a
// node that may emit towards the receiver never gets importance 0 (wide spot cones have
// theta_e > pi/2 and would otherwise get a negative cosine).
constexpr float kMinCosine = 1e-2f;
// From this depth on the build splits at the median, so a path has at most 40 + log2(n) nodes.
constexpr int kMedianDepth = 40;
constexpr int kMaxDepth = kMedianDepth + 64;
constexpr int kBins = 12;

float angle_between(Vec3 a, Vec3 b) { return std::acos(std::clamp(dot(a, b), -1.0f, 1.0f)); }

// Rotates v (unit) about the unit axis k perpendicular to it.
Vec3 rotate_perpendicular(Vec3 v, Vec3 k, float angle) {
  return v * std::cos(angle) + cross(k, v) * std::sin(angle);
}

struct Cone {
  Vec3 w;
  float theta;
};

// The narrowest cone holding both (the paper's Algorithm 1).
Cone merge_cones(Cone a, Cone b) {
  if (a.theta < b.theta) std::swap(a, b);
  const float theta_d = angle_between(a.w, b.w);
  if (std::min(theta_d + b.theta, kPi) <= a.theta) return a;
  const float theta_o = 0.5f * (a.theta + theta_d + b.theta);
  if (theta_o >= kPi) return {a.w, kPi};
  const Vec3 k = cross(a.w, b.w);
  if (!(length_squared(k) > 1e-12f)) return {a.w, kPi};
  return {normalize(rotate_perpendicular(a.w, normalize(k), theta_o - a.theta)), theta_o};
}

// cos(max(0, a - b)) and sin(max(0, a - b)) from the angles' cosines and sines (a, b in [0, pi]).
float cos_sub_clamped(float cos_a, float sin_a, float cos_b, float sin_b) {
  return cos_a >= cos_b ? 1.0f : cos_a * cos_b + sin_a * sin_b;
}
float sin_sub_clamped(float cos_a, float sin_a, float cos_b, float sin_b) {
  return cos_a >= cos_b ? 0.0f : sin_a * cos_b - cos_a * sin_b;
}

// cos theta': the smallest angle between an emission direction the node allows and the
// receiver, given the angle theta_w between the axis and the direction from the centre to the
// receiver and the half-angle theta_b of the bounding sphere. 0 when the node cannot emit there.
float emission_cosine(const LightTree::Node& node, float cos_w, float sin_w, float cos_b, float sin_b) {
  const float cos_x = cos_sub_clamped(cos_w, sin_w, node.cos_theta_o, node.sin_theta_o);
  const float sin_x = sin_sub_clamped(cos_w, sin_w, node.cos_theta_o, node.sin_theta_o);
  const float cos_p = cos_sub_clamped(cos_x, sin_x, cos_b, sin_b);
  return cos_p > node.cos_theta_e ? std::max(cos_p, kMinCosine) : 0.0f;
}

// The paper's orientation measure M_Omega: the cone's emission integrated with the cosine.
float orientation_measure(const LightBounds& b) {
  const float theta_o = std::acos(std::clamp(b.cos_theta_o, -1.0f, 1.0f));
  const float theta_e = std::acos(std::clamp(b.cos_theta_e, -1.0f, 1.0f));
  const float theta_w = std::min(theta_o + theta_e, kPi);
  const float sin_o = std::sin(theta_o), cos_o = std::cos(theta_o);
  return 2.0f * kPi * (1.0f - cos_o) +
         0.5f * kPi * (2.0f * theta_w * sin_o - std::cos(theta_o - 2.0f * theta_w) - 2.0f * theta_o * sin_o + cos_o);
}

// The split cost of a cluster: power x surface area (padded, so points and lines differ) x M_Omega.
float cluster_cost(const LightBounds& b, float pad) {
  if (b.box.empty()) return 0.0f;
  const Vec3 d = b.box.diagonal() + Vec3(pad);
  return b.phi * 2.0f * (d.x * d.y + d.y * d.z + d.z * d.x) * orientation_measure(b);
}

Vec3 centroid(const LightBounds& b) { return b.box.center(); }

using Items = std::vector<std::pair<int, LightBounds>>;

struct CentroidBins {
  Bounds3 centroids;
  Vec3 extent;
  int bin(const LightBounds& b, int axis) const {
    return std::min(kBins - 1, int(kBins * (centroid(b)[axis] - centroids.lo[axis]) / extent[axis]));
  }
};

struct Split {
  int axis = -1, bin = -1;
  float cost = kInfinity;
};

// Binned SAOH: the split of least cost(left) + cost(right), scaled by Kr = max extent / extent.
Split best_saoh_split(const Items& items, size_t begin, size_t end, const CentroidBins& cb) {
  const float max_extent = max_component(cb.extent);
  const float pad = 1e-3f * max_extent;
  Split best;
  for (int axis = 0; axis < 3; ++axis) {
    if (!(cb.extent[axis] > 0.0f)) continue;
    std::array<LightBounds, kBins> bins{};
    for (size_t i = begin; i < end; ++i) {
      LightBounds& bin = bins[size_t(cb.bin(items[i].second, axis))];
      bin = merge(bin, items[i].second);
    }
    std::array<LightBounds, kBins> right{};  // right[b]: bins b and above
    right[kBins - 1] = bins[kBins - 1];
    for (int b = kBins - 2; b > 0; --b) right[size_t(b)] = merge(right[size_t(b) + 1], bins[size_t(b)]);
    LightBounds left;
    for (int b = 0; b + 1 < kBins; ++b) {
      left = merge(left, bins[size_t(b)]);
      if (left.box.empty() || right[size_t(b) + 1].box.empty()) continue;
      const float cost =
          (max_extent / cb.extent[axis]) * (cluster_cost(left, pad) + cluster_cost(right[size_t(b) + 1], pad));
      if (cost < best.cost) best = {axis, b, cost};
    }
  }
  return best;
}

// Reorders items[begin, end) into two non-empty halves and returns where the second starts:
// by SAOH above kMedianDepth, else (or when SAOH finds no split) at the median along the widest
// centroid axis (also for coincident lights).
size_t split(Items& items, size_t begin, size_t end, int depth) {
  CentroidBins cb;
  for (size_t i = begin; i < end; ++i) cb.centroids.extend(centroid(items[i].second));
  cb.extent = cb.centroids.diagonal();
  const auto first = items.begin() + std::ptrdiff_t(begin), last = items.begin() + std::ptrdiff_t(end);
  if (depth < kMedianDepth && max_component(cb.extent) > 0.0f) {
    const Split s = best_saoh_split(items, begin, end, cb);
    if (s.axis >= 0) {
      const size_t mid = size_t(
          std::partition(first, last, [&](const auto& it) { return cb.bin(it.second, s.axis) <= s.bin; }) -
          items.begin());
      if (mid > begin && mid < end) return mid;
    }
  }
  int axis = 0;
  for (int a = 1; a < 3; ++a)
    if (cb.extent[a] > cb.extent[axis]) axis = a;
  const size_t mid = (begin + end) / 2;
  std::nth_element(first, items.begin() + std::ptrdiff_t(mid), last, [axis](const auto& a, const auto& b) {
    return centroid(a.second)[axis] < centroid(b.second)[axis];
  });
  return mid;
}

}  // namespace

LightBounds bounds_at_point(Vec3 p, float phi, Vec3 axis, float cos_o, float cos_e) {
  LightBounds b;
  b.box.extend(p);
  b.phi = phi;
  b.axis = axis;
  b.cos_theta_o = cos_o;
  b.cos_theta_e = cos_e;
  return b;
}

LightBounds bounds_of_flat(std::initializer_list<Vec3> corners, Vec3 normal, bool two_sided, float phi) {
  LightBounds b;
  for (Vec3 c : corners) b.box.extend(c);
  b.phi = phi;
  const float len = length(normal);
  const bool any = two_sided || !(len > 0.0f);
  b.axis = any ? Vec3(0, 0, 1) : normal / len;
  b.cos_theta_o = any ? -1.0f : 1.0f;
  b.cos_theta_e = kCosHemisphere;
  return b;
}


LightBounds merge(const LightBounds& a, const LightBounds& b) {
  if (a.box.empty()) return b;
  if (b.box.empty()) return a;
  LightBounds m;
  m.box = a.box;
  m.box.extend(b.box);
  m.phi = a.phi + b.phi;
  const Cone c = merge_cones({a.axis, std::acos(std::clamp(a.cos_theta_o, -1.0f, 1.0f))},
                             {b.axis, std::acos(std::clamp(b.cos_theta_o, -1.0f, 1.0f))});
  m.axis = c.w;
  m.cos_theta_o = c.theta >= kPi ? -1.0f : std::cos(c.theta);
  m.cos_theta_e = std::min(a.cos_theta_e, b.cos_theta_e);
  return m;
}

LightTree::Node LightTree::make_node(const LightBounds& b) {
  Node n;
  n.centre = b.box.center();
  n.radius = 0.5f * length(b.box.diagonal());
  n.phi = b.phi;
  n.axis = b.axis;
  n.cos_theta_o = b.cos_theta_o;
  n.sin_theta_o = safe_sqrt(1.0f - sqr(b.cos_theta_o));
  n.cos_theta_e = b.cos_theta_e;
  return n;
}

float LightTree::importance(const Node& node, Vec3 p, Vec3 n) {
  const Vec3 to_p = p - node.centre;
  const float d2 = length_squared(to_p);
  float cos_emit = 1.0f, cos_receive = 1.0f;  // theta_b = pi inside the bounding sphere
  if (d2 > sqr(node.radius)) {
    const float d = std::sqrt(d2);
    const float sin_b = node.radius / d, cos_b = safe_sqrt(1.0f - sqr(sin_b));
    const Vec3 v = to_p / d;
    const float cos_w = std::clamp(dot(node.axis, v), -1.0f, 1.0f);
    cos_emit = emission_cosine(node, cos_w, safe_sqrt(1.0f - sqr(cos_w)), cos_b, sin_b);
    if (length_squared(n) > 0.0f) {
      const float cos_i = std::clamp(-dot(n, v), -1.0f, 1.0f);
      const float c = cos_sub_clamped(cos_i, safe_sqrt(1.0f - sqr(cos_i)), cos_b, sin_b);
      cos_receive = c > 0.0f ? std::max(c, kMinCosine) : 0.0f;
    }
  }
  const float d2_floor = std::max({d2, 0.25f * sqr(node.radius), 1e-12f});
  return node.phi * cos_emit * cos_receive / d2_floor;
}

namespace {

// atan2(y, x) for y >= 0 (a minimax polynomial, error < 1e-5 rad; 0 only for y = 0). The
// importance needs no more, and it is ~20 % of a many-lights render with libm's atan.
float fast_atan2_upper(float y, float x) {
  const float ax = std::abs(x);
  const float t = std::min(ax, y) / std::max(std::max(ax, y), 1e-30f);
  const float t2 = t * t;
  float a = t * (0.99997726f + t2 * (-0.33262347f + t2 * (0.19354346f + t2 * (-0.11643287f + t2 * (0.05265332f - t2 * 0.01172120f)))));
  if (y > ax) a = 0.5f * kPi - a;
  return x < 0.0f ? kPi - a : a;
}

// The angle the line points at parameters a <= b (relative to the foot of the perpendicular)
// subtend from a point at distance h > 0 from the line: atan(b/h) - atan(a/h), b may be infinite.
float subtended_angle(float a, float b, float h) {
  if (std::isinf(b)) return fast_atan2_upper(h, a);  // pi/2 - atan(a/h)
  return fast_atan2_upper(h * (b - a), h * h + a * b);
}

// The cosine of the smallest angle between `axis` and the directions from `c` to the points of
// the segment: an arc of a great circle from v0 to v1 in the plane of the line and c.
float closest_arc_cosine(Vec3 axis, const Ray& s, Vec3 c, float h_line) {
  const Vec3 v0 = normalize(s.at(s.tmin) - c);
  const Vec3 v1 = std::isinf(s.tmax) ? s.direction : normalize(s.at(s.tmax) - c);
  float best = std::max(dot(axis, v0), dot(axis, v1));
  if (h_line > 0.0f) {
    const Vec3 m = cross(s.origin - c, s.direction) / h_line;  // the arc turns from v0 to v1 about m
    const Vec3 wp = axis - m * dot(axis, m);
    if (dot(cross(v0, wp), m) >= 0.0f && dot(cross(wp, v1), m) >= 0.0f) best = std::max(best, length(wp));
  }
  return std::clamp(best, -1.0f, 1.0f);
}

}  // namespace

float LightTree::importance(const Node& node, const Ray& s) {
  const Vec3 oc = node.centre - s.origin;
  const float tc = dot(oc, s.direction);
  const float h_line = length(cross(oc, s.direction));
  // The integral of 1/d^2 along the segment for an emitter at the (floored) line distance h.
  const float h = std::max({h_line, 0.5f * node.radius, 1e-6f});
  const float theta_d = subtended_angle(s.tmin - tc, s.tmax - tc, h);
  if (!(theta_d > 0.0f)) return 0.0f;
  const float t_closest = std::clamp(tc, s.tmin, s.tmax);
  const float d_min = length(s.at(t_closest) - node.centre);
  float cos_emit = 1.0f;
  if (d_min > node.radius && node.cos_theta_o > -1.0f) {
    const float sin_b = node.radius / d_min, cos_b = safe_sqrt(1.0f - sqr(sin_b));
    const float cos_w = closest_arc_cosine(node.axis, s, node.centre, h_line);
    cos_emit = emission_cosine(node, cos_w, safe_sqrt(1.0f - sqr(cos_w)), cos_b, sin_b);
  }
  return node.phi * cos_emit * theta_d / h;
}

LightTree::LightTree(std::span<const Light> lights, std::span<const int> members) {
  leaf_of_.assign(lights.size(), -1);
  std::vector<std::pair<int, LightBounds>> items;
  for (int i : members)
    if (const auto b = light_bounds(lights[size_t(i)]); b && b->phi > 0.0f) items.emplace_back(i, *b);
  if (items.empty()) return;
  nodes_.reserve(2 * items.size());
  parent_.reserve(2 * items.size());
  build(items, 0, items.size(), 0);
}

int LightTree::build(std::vector<std::pair<int, LightBounds>>& items, size_t begin, size_t end, int depth) {
  const int index = int(nodes_.size());
  LightBounds all = items[begin].second;
  for (size_t i = begin + 1; i < end; ++i) all = merge(all, items[i].second);
  nodes_.push_back(make_node(all));
  parent_.push_back(-1);
  if (end - begin == 1) {
    nodes_[size_t(index)].child[0] = items[begin].first;
    leaf_of_[size_t(items[begin].first)] = index;
    return index;
  }
  const size_t mid = split(items, begin, end, depth);
  const int left = build(items, begin, mid, depth + 1);
  const int right = build(items, mid, end, depth + 1);
  nodes_[size_t(index)].child[0] = left;
  nodes_[size_t(index)].child[1] = right;
  parent_[size_t(left)] = parent_[size_t(right)] = index;
  return index;
}

// The same products as descend(), from the root down to the light's leaf; a node that
// `split(node, depth)` says is split contributes 1 (both children are taken).
template <class Importance, class Split>
float LightTree::path_pmf(int light, const Importance& importance, const Split& split) const {
  if (light < 0 || size_t(light) >= leaf_of_.size() || leaf_of_[size_t(light)] < 0) return 0.0f;
  std::array<int, kMaxDepth + 1> path;
  int length = 0;
  for (int node = leaf_of_[size_t(light)]; node >= 0; node = parent_[size_t(node)]) path[size_t(length++)] = node;
  float pmf = 1.0f;
  for (int k = length - 1; k > 0; --k) {
    const Node& n = nodes_[size_t(path[size_t(k)])];
    if (split(n, length - 1 - k)) {
      if (!(importance(nodes_[size_t(path[size_t(k - 1)])]) > 0.0f)) return 0.0f;  // skipped by descend_split
      continue;
    }
    const float i0 = importance(nodes_[size_t(n.child[0])]), i1 = importance(nodes_[size_t(n.child[1])]);
    if (!(i0 + i1 > 0.0f)) return 0.0f;
    const float p0 = i0 / (i0 + i1);
    pmf *= path[size_t(k - 1)] == n.child[0] ? p0 : 1.0f - p0;
  }
  return pmf;
}

// From `node` at `depth` to a leaf: one uniform number picks a child per level in proportion to
// importance, rescaled to [0, 1) within the chosen share; both children of every node `split`
// names are taken. Nothing is added below a node whose children both have importance 0.
template <class Importance, class Split>
void LightTree::descend_split(int node, int depth, float u, float pmf, float scale, const Importance& importance,
                              const Split& split, LightChoices& out) const {
  while (!nodes_[size_t(node)].leaf()) {
    const Node& n = nodes_[size_t(node)];
    if (split(n, depth)) {
      // A side of importance 0 cannot light the receiver (the bounds are conservative): skipped,
      // as path_pmf skips it, so it costs no shadow ray.
      const bool left = importance(nodes_[size_t(n.child[0])]) > 0.0f;
      const bool right = importance(nodes_[size_t(n.child[1])]) > 0.0f;
      if (!right) {
        if (!left) return;
        node = n.child[0];
        ++depth;
        continue;
      }
      if (left) descend_split(n.child[0], depth + 1, u, pmf, scale, importance, split, out);
      // The other side takes u shifted by the golden ratio (mod 1): still uniform, so its choice
      // is unbiased, but not the same choice as this side's (with one u for both, small u picked
      // the first light of every subtree at once, and the correlated sum was noisier).
      u += 0.618034f;
      if (u >= 1.0f) u -= 1.0f;
      u = std::min(u, kOneMinusEpsilon);
      node = n.child[1];
      ++depth;
      continue;
    }
    const float i0 = importance(nodes_[size_t(n.child[0])]), i1 = importance(nodes_[size_t(n.child[1])]);
    if (!(i0 + i1 > 0.0f)) return;
    const float p0 = i0 / (i0 + i1);
    if (u < p0) {
      u = std::min(u / p0, kOneMinusEpsilon);
      pmf *= p0;
      node = n.child[0];
    } else {
      u = std::min((u - p0) / (1.0f - p0), kOneMinusEpsilon);
      pmf *= 1.0f - p0;
      node = n.child[1];
    }
    ++depth;
  }
  out.add({nodes_[size_t(node)].child[0], scale * pmf});  // in the order pmf_tree multiplies
}

namespace {
constexpr auto kNoSplit = [](const LightTree::Node&, int) { return false; };
}  // namespace

// One light: the descent without splits (light -1 when both children of a node have importance 0).
template <class Importance>
LightChoice LightTree::descend(float u, const Importance& importance) const {
  if (nodes_.empty()) return {};
  LightChoices out;
  descend_split(0, 0, u, 1.0f, 1.0f, importance, kNoSplit, out);
  return out.count > 0 ? out.choice[0] : LightChoice{};
}

namespace {

// Whether a node is split for a receiving point or segment (see the header).
bool split_at(const LightTree::Node& n, int depth, float distance) {
  return depth < LightTree::kSplitDepth && !n.leaf() && n.radius > LightTree::kSplitRatio * distance;
}

float distance_to_segment(Vec3 c, const Ray& s) {
  const float t = std::clamp(dot(c - s.origin, s.direction), s.tmin, s.tmax);
  return length(c - s.at(t));
}

}  // namespace

LightChoice LightTree::sample(Vec3 p, Vec3 n, float u) const {
  return descend(u, [&](const Node& node) { return importance(node, p, n); });
}

float LightTree::pmf(Vec3 p, Vec3 n, int light) const {
  return path_pmf(light, [&](const Node& node) { return importance(node, p, n); }, kNoSplit);
}

LightChoice LightTree::sample_segment(const Ray& segment, float u) const {
  return descend(u, [&](const Node& node) { return importance(node, segment); });
}

float LightTree::pmf_segment(const Ray& segment, int light) const {
  return path_pmf(light, [&](const Node& node) { return importance(node, segment); }, kNoSplit);
}

void LightTree::sample_split(Vec3 p, Vec3 n, float u, float scale, LightChoices& out) const {
  if (nodes_.empty()) return;
  descend_split(
      0, 0, u, 1.0f, scale, [&](const Node& node) { return importance(node, p, n); },
      [&](const Node& node, int depth) { return split_at(node, depth, length(node.centre - p)); }, out);
}

float LightTree::split_pmf(Vec3 p, Vec3 n, int light) const {
  return path_pmf(
      light, [&](const Node& node) { return importance(node, p, n); },
      [&](const Node& node, int depth) { return split_at(node, depth, length(node.centre - p)); });
}

void LightTree::sample_split_segment(const Ray& segment, float u, float scale, LightChoices& out) const {
  if (nodes_.empty()) return;
  descend_split(
      0, 0, u, 1.0f, scale, [&](const Node& node) { return importance(node, segment); },
      [&](const Node& node, int depth) { return split_at(node, depth, distance_to_segment(node.centre, segment)); },
      out);
}

float LightTree::split_pmf_segment(const Ray& segment, int light) const {
  return path_pmf(
      light, [&](const Node& node) { return importance(node, segment); },
      [&](const Node& node, int depth) { return split_at(node, depth, distance_to_segment(node.centre, segment)); });
}

}  // namespace caligo
