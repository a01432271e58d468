// Choosing which light next-event estimation samples: one seam, three strategies.
//
//   uniform  every light with probability 1 / (number of lights)
//   power    in proportion to power(light), the same everywhere (the former selection)
//   tree     the light tree (lights/light_tree.h) for finite lights, importance at the
//            receiver; lights at infinity (directional, environment) beside it
//
// Rule for lights at infinity under `tree`: they are chosen with a fixed probability
// P_inf = their share of the total power, clamped to [0.1, 0.9] when both kinds exist
// (1 when only lights at infinity have power, 0 when none do), and among themselves in
// proportion to power; the tree gets 1 - P_inf. Lights of zero power are never chosen (by
// power and tree).
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

  LightSamplerKind kind() const;

  // A receiving point; n is the unit normal facing the side light may arrive from, or zero
  // (media, transmitting surfaces). u in [0, 1).
  LightChoice sample(Vec3 p, Vec3 n, float u) const;
  float pmf(Vec3 p, Vec3 n, int light) const;
  // One light for a whole ray segment in a medium: origin, unit direction, [tmin, tmax].
  LightChoice sample_segment(const Ray& segment, float u) const;
  float pmf_segment(const Ray& segment, int light) const;
  // False when the choice does not depend on u (one light): callers skip drawing it.
  bool needs_random() const { return single_ < 0; }

 private:
  struct Uniform {
    int count = 0;
  };
  struct Power {
    DiscreteDistribution distribution;  // empty when no light has power
  };
  struct Tree {
    LightTree tree;
    DiscreteDistribution infinite;  // over infinite_lights, by power
    std::vector<int> infinite_lights;
    std::vector<int> infinite_slot;  // per light: its index in infinite_lights, or -1
    float infinite_probability = 0.0f;
  };
  template <class TreeSample>
  LightChoice sample_tree(const Tree& t, float u, const TreeSample& tree_sample) const;
  template <class TreePmf>
  float pmf_tree(const Tree& t, int light, const TreePmf& tree_pmf) const;

  std::variant<Power, Uniform, Tree> strategy_;
  int single_ = -1;  // the only light, when there is exactly one of positive power
};

}  // namespace caligo
