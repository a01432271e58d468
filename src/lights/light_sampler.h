// Choosing which light next-event estimation samples: one seam, three strategies.
//
//   uniform  every light with probability 1 / (number of lights)
//   power    in proportion to power(light), the same everywhere (the former selection)
//   tree     the light tree (lights/light_tree.h) for finite lights, importance at the
//            receiver; lights at infinity (directional, environment) beside it
//
// Rule for lights at infinity under `tree`: they are weighed at the receiver like the tree's
// nodes. A node's importance is power x cosines / d^2, which for a point light is 4 pi times
// the irradiance it gives; a light at infinity gives 4 pi times its own: a sun E cos (E alone
// in a medium), an environment of fluence F = integral of L over the sphere F / 4 on a surface
// (its cosine-weighted hemisphere, were it uniform) and F in a medium. For a segment both are
// integrated along it (the tree by theta_d / h, a light at infinity times the segment's length,
// at most the scene's diameter). P_inf = I_inf / (I_inf + I_tree) clamped to [0.05, 0.95]
// when both kinds exist (1 when only lights at infinity have power, 0 when none do), and among
// themselves by their importance (by fluence where none has any); the tree gets 1 - P_inf.
// The former rule, a fixed P_inf = their share of the total power clamped to [0.1, 0.9], is
// `tree-fixed-share`: an environment's power grows with the scene's bounds (pi r^2 F), so a
// large ground plane handed the sky up to 90 % of the samples. Lights of zero power are never
// chosen (by power and tree).
//
// pmf() and pmf_segment() return exactly the probability with which sample() and
// sample_segment() choose a light at that receiver (the MIS weight of a BSDF- or
// phase-sampled hit on any light needs it). Power and uniform ignore the receiver.
//
// Immutable after construction; shared read-only by all render threads.
#pragma once

#include <optional>
#include <span>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "core/ray.h"
#include "core/sampling.h"
#include "lights/light.h"
#include "lights/light_tree.h"
#include "settings/light_sampler_kind.h"

namespace caligo {

// "uniform", "power", "tree"; nullopt for anything else.
std::optional<LightSamplerKind> light_sampler_from_name(std::string_view name);
const char* light_sampler_name(LightSamplerKind kind);

class LightSampler {
 public:
  LightSampler() = default;  // no lights: sample() chooses nothing
  LightSampler(LightSamplerKind kind, std::span<const Light> lights);

  // A receiving point; n is the unit normal facing the side light may arrive from, or zero
  // (media, transmitting surfaces). u in [0, 1).
  LightChoice sample(Vec3 p, Vec3 n, float u) const;
  float pmf(Vec3 p, Vec3 n, int light) const;
  // One light for a whole ray segment in a medium: origin, unit direction, [tmin, tmax].
  LightChoice sample_segment(const Ray& segment, float u) const;
  float pmf_segment(const Ray& segment, int light) const;
  // Next-event estimation's choice: the lights one estimate connects to, each with the
  // probability that it is among them (the light tree's adaptive splitting, LightTree::
  // sample_split, may choose several; every other strategy chooses one, as sample() does), and
  // that probability for any light at the receiver (what MIS weights a hit on it by).
  LightChoices choose(Vec3 p, Vec3 n, float u) const;
  float choice_pmf(Vec3 p, Vec3 n, int light) const;
  LightChoices choose_segment(const Ray& segment, float u) const;
  float choice_pmf_segment(const Ray& segment, int light) const;
  // False when the choice does not depend on u (one light): callers skip drawing it.
  bool needs_random() const { return single_ < 0; }

 private:
  struct Uniform {
    int count = 0;
  };
  struct Power {
    DiscreteDistribution distribution;  // empty when no light has power
  };
  // A light at infinity as the receiver-side rule sees it (public for the builder).
 public:
  struct Infinite {
    int light;
    float fluence;      // power / (pi r^2): irradiance of a sun, integral of L of an environment
    Vec3 towards;       // a sun's direction towards it; zero for an environment
    float sin_radius;   // a sun's angular radius (a margin on its cosine)
  };

 private:
  struct Tree {
    LightTree tree;
    std::vector<Infinite> infinite_at;  // the lights at infinity of positive power
    DiscreteDistribution infinite;      // over infinite_at, by power (the fixed-share rule)
    std::vector<int> infinite_slot;     // per light: its index in infinite_at, or -1
    float infinite_probability = 0.0f;  // the fixed share; < 0: weighed at the receiver
    bool split = false;                 // choose() splits the tree (LightTree::sample_split)
    float scene_diameter = 2.0f;
  };
  // A receiver: a point with its normal (zero: none), or a segment.
  struct Receiver {
    Vec3 p, n;
    const Ray* segment = nullptr;
  };
  static float infinite_importance(const Infinite& l, const Receiver& r, float diameter);
  std::pair<float, float> infinite_share(const Tree& t, const Receiver& r) const;
  LightChoice sample_tree(const Tree& t, float u, const Receiver& r) const;
  float pmf_tree(const Tree& t, int light, const Receiver& r, bool split = false) const;
  LightChoices choose_tree(const Tree& t, float u, const Receiver& r) const;

  std::variant<Power, Uniform, Tree> strategy_;
  int single_ = -1;  // the only light, when there is exactly one of positive power
};

}  // namespace caligo
