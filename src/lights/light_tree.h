// A light BVH for choosing one of many lights by its importance at a receiver (Conty Estevez
// & Kulla 2017, "Importance Sampling of Many Lights with Adaptive Tree Splitting").
//
// Every node bounds its lights by a bounding sphere (centre, radius), their total power
// (W) and an orientation cone: every emitter normal lies within theta_o of `axis`, and each
// emits only within theta_e of its normal. A node's importance at a receiver is
//   power * cos(theta') * [cos(theta_i')] / d^2
// where theta' is the smallest angle between any emission direction the cone allows and the
// direction towards the receiver (bounded with the angle the sphere subtends), theta_i' the
// smallest angle between the receiver's normal and the node (surfaces only), d the distance
// to the centre (floored at half the radius). For a ray segment (a medium's next-event
// estimation chooses one light for the whole segment) the inverse square becomes its
// integral along the segment, theta_d / h (the angle the segment subtends at the centre over
// the line's distance from it, the equiangular integral), and theta' the smallest angle over
// every point of the segment. Both are conservative: a node that can light the receiver never
// has importance 0.
//
// Sampling descends from the root, choosing a child in proportion to its importance with
// one uniform number (rescaled at each level); the pmf is the product of the choices, and
// pmf() recomputes exactly that product for any light (the same operations in the same order,
// so equal bit for bit). Adaptive splitting (sample_split, below) takes both children of nodes
// that are close to the receiver. Deviations from the paper: one light per leaf, a split
// criterion on the node's size over its distance alone (not its emission variance); the build uses the paper's SAOH cost with 12 bins per axis, falling back to median splits
// from depth 40 on, so paths stay short (at most 40 + log2(lights) nodes).
//
// Units: positions in metres, powers in W. Immutable after construction; any number of
// threads may sample it concurrently.
#pragma once

#include <array>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <span>
#include <vector>

#include "core/bounds.h"
#include "core/ray.h"
#include "lights/light.h"

namespace caligo {

// What a light or a cluster of lights looks like from far away.
struct LightBounds {
  Bounds3 box;             // every emitting point
  float phi = 0.0f;        // power, W
  Vec3 axis{0, 0, 1};      // unit
  float cos_theta_o = -1;  // normals within theta_o of axis (-1: any)
  float cos_theta_e = 0;   // emission within theta_e of the normal (0: a hemisphere)
};

// The bounds of a finite light; nullopt for lights at infinity.
std::optional<LightBounds> light_bounds(const Light& light);
// theta_e = pi/2, kept as exactly 0 (cos(pi/2) in float is -4e-8).
constexpr float kCosHemisphere = 0.0f;
// A point (or the first point of a box) emitting phi watts about `axis`.
LightBounds bounds_at_point(Vec3 p, float phi, Vec3 axis, float cos_o, float cos_e);
// A flat emitter with the given corners: one-sided ones emit into the hemisphere about the
// normal, two-sided ones about either side.
LightBounds bounds_of_flat(std::initializer_list<Vec3> corners, Vec3 normal, bool two_sided, float phi);
// The smallest bounds holding both (cones merged as in the paper).
LightBounds merge(const LightBounds& a, const LightBounds& b);

struct LightChoice {
  int light = -1;  // index into the scene's lights; -1: nothing chosen
  float pmf = 0.0f;
};

// The lights one next-event estimate connects to under adaptive splitting: at most one per
// subtree the split reached, each with the probability that it is among them.
struct LightChoices {
  static constexpr int kMax = 8;  // 2^LightTree::kSplitDepth (a light at infinity is chosen instead)
  std::array<LightChoice, kMax> choice{};
  int count = 0;
  void add(LightChoice c) {
    if (c.light >= 0 && count < kMax) choice[size_t(count++)] = c;
  }
  const LightChoice* begin() const { return choice.data(); }
  const LightChoice* end() const { return choice.data() + count; }
};

class LightTree {
 public:
  LightTree() = default;
  // Builds over lights[i] for every i in `members` (finite lights of positive power).
  LightTree(std::span<const Light> lights, std::span<const int> members);

  bool empty() const { return nodes_.empty(); }
  // n: unit normal of the receiving surface, facing the side where light can arrive; zero
  // for no normal (a point in a medium, or a surface that transmits).
  LightChoice sample(Vec3 p, Vec3 n, float u) const;
  float pmf(Vec3 p, Vec3 n, int light) const;
  // segment: origin, unit direction and [tmin, tmax] (tmax may be infinite).
  LightChoice sample_segment(const Ray& segment, float u) const;
  float pmf_segment(const Ray& segment, int light) const;

  // Adaptive splitting (Conty Estevez & Kulla 2017, section 5.3): a node whose bounding sphere is
  // large against its distance from the receiver (radius > kSplitRatio x distance: its
  // importance, ~ 1 / d^2 over the sphere, then spans a factor of 9 or more) is not chosen
  // between but descended on both sides, to depth kSplitDepth; below a node that is not
  // split the descent is the stochastic one above, with the same u rescaled. The pmf of a
  // light is the probability that it is among the choices: the product of the stochastic
  // choices on its path (a split counts 1), recomputed by split_pmf exactly. The split depends
  // on the node and the receiver alone, so that pmf needs no other branch.
  static constexpr int kSplitDepth = 3;
  static constexpr float kSplitRatio = 0.5f;
  static_assert(LightChoices::kMax >= 1 << kSplitDepth, "a split may reach every subtree");
  void sample_split(Vec3 p, Vec3 n, float u, float scale, LightChoices& out) const;
  float split_pmf(Vec3 p, Vec3 n, int light) const;
  void sample_split_segment(const Ray& segment, float u, float scale, LightChoices& out) const;
  float split_pmf_segment(const Ray& segment, int light) const;

  // The importance of a bounds at a point or for a segment (exposed for tests).
  struct Node;
  static float importance(const Node& node, Vec3 p, Vec3 n);
  static float importance(const Node& node, const Ray& segment);
  // The root's: what all the tree's lights together bound at a receiver (0 when empty).
  float root_importance(Vec3 p, Vec3 n) const { return empty() ? 0.0f : importance(nodes_[0], p, n); }
  float root_importance(const Ray& segment) const { return empty() ? 0.0f : importance(nodes_[0], segment); }

  struct Node {
    Vec3 centre;
    float radius = 0.0f;
    float phi = 0.0f;
    Vec3 axis;
    float cos_theta_o = -1.0f, sin_theta_o = 0.0f;
    float cos_theta_e = 0.0f;
    int child[2] = {-1, -1};  // interior: both children; leaf: child[0] is the light, child[1] = -1
    bool leaf() const { return child[1] < 0; }
  };
  static Node make_node(const LightBounds& b);
  size_t node_count() const { return nodes_.size(); }

 private:
  int build(std::vector<std::pair<int, LightBounds>>& items, size_t begin, size_t end, int depth);
  template <class Importance>
  LightChoice descend(float u, const Importance& importance) const;
  template <class Importance, class Split>
  float path_pmf(int light, const Importance& importance, const Split& split) const;
  template <class Importance, class Split>
  void descend_split(int node, int depth, float u, float pmf, float scale, const Importance& importance,
                     const Split& split, LightChoices& out) const;

  std::vector<Node> nodes_;      // nodes_[0] is the root
  std::vector<int> parent_;      // per node; -1 for the root
  std::vector<int> leaf_of_;     // per scene light: its leaf node, or -1 when not in the tree
};

}  // namespace caligo
