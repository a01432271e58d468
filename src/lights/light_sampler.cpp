#include "lights/light_sampler.h"

#include <algorithm>

#include "core/overloaded.h"

namespace caligo {
namespace {

constexpr float kMinInfiniteShare = 0.1f, kMaxInfiniteShare = 0.9f;

// Power selection's weights: max(0, power), as the former selection used (bit for bit).
std::vector<float> power_weights(std::span<const Light> lights) {
  std::vector<float> weights;
  for (const Light& light : lights) weights.push_back(std::max(0.0f, power(light)));
  return weights;
}

DiscreteDistribution distribution_or_empty(std::span<const float> weights) {
  float total = 0.0f;
  for (float w : weights) total += w;
  return total > 0.0f ? DiscreteDistribution(weights) : DiscreteDistribution();
}

}  // namespace

std::optional<LightSamplerKind> light_sampler_from_name(std::string_view name) {
  return enum_from_name(kLightSamplerNames, name);
}

const char* light_sampler_name(LightSamplerKind kind) { return enum_name(kLightSamplerNames, kind).data(); }

LightSampler::LightSampler(LightSamplerKind kind, std::span<const Light> lights) {
  // One light of positive power: every strategy chooses it with probability 1 (the tree's
  // importance bounds would only cut off receivers it cannot light, where its contribution is
  // zero anyway), and no random number is needed.
  if (lights.size() == 1 && power(lights[0]) > 0.0f) single_ = 0;
  switch (kind) {
    case LightSamplerKind::kUniform:
      strategy_ = Uniform{int(lights.size())};
      return;
    case LightSamplerKind::kPower:
      strategy_ = Power{distribution_or_empty(power_weights(lights))};
      return;
    case LightSamplerKind::kTree: break;
  }
  Tree t;
  std::vector<int> finite;
  std::vector<float> infinite_weights;
  float finite_power = 0.0f, infinite_power = 0.0f;
  t.infinite_slot.assign(lights.size(), -1);
  for (size_t i = 0; i < lights.size(); ++i) {
    const float phi = std::max(0.0f, power(lights[i]));
    if (!(phi > 0.0f)) continue;
    if (is_infinite(lights[i])) {
      t.infinite_slot[i] = int(t.infinite_lights.size());
      t.infinite_lights.push_back(int(i));
      infinite_weights.push_back(phi);
      infinite_power += phi;
    } else {
      finite.push_back(int(i));
      finite_power += phi;
    }
  }
  t.tree = LightTree(lights, finite);
  if (!t.infinite_lights.empty()) t.infinite = DiscreteDistribution(infinite_weights);
  if (t.tree.empty())
    t.infinite_probability = t.infinite_lights.empty() ? 0.0f : 1.0f;
  else if (!t.infinite_lights.empty())
    t.infinite_probability =
        std::clamp(infinite_power / (infinite_power + finite_power), kMinInfiniteShare, kMaxInfiniteShare);
  strategy_ = std::move(t);
}

LightSamplerKind LightSampler::kind() const {
  if (std::holds_alternative<Uniform>(strategy_)) return LightSamplerKind::kUniform;
  if (std::holds_alternative<Power>(strategy_)) return LightSamplerKind::kPower;
  return LightSamplerKind::kTree;
}

template <class TreeSample>
LightChoice LightSampler::sample_tree(const Tree& t, float u, const TreeSample& tree_sample) const {
  const float p_inf = t.infinite_probability;
  if (u < p_inf) {
    float pmf = 0.0f;
    const int k = t.infinite.sample(std::min(u / p_inf, kOneMinusEpsilon), &pmf);
    return {t.infinite_lights[size_t(k)], p_inf * pmf};
  }
  if (t.tree.empty()) return {};
  LightChoice c = tree_sample(std::min((u - p_inf) / (1.0f - p_inf), kOneMinusEpsilon));
  c.pmf = (1.0f - p_inf) * c.pmf;
  return c;
}

template <class TreePmf>
float LightSampler::pmf_tree(const Tree& t, int light, const TreePmf& tree_pmf) const {
  const int slot = t.infinite_slot[size_t(light)];
  if (slot >= 0) return t.infinite_probability * t.infinite.pmf(slot);
  if (t.tree.empty()) return 0.0f;
  return (1.0f - t.infinite_probability) * tree_pmf();
}

// Power and uniform: the receiver does not matter.
namespace {

LightChoice sample_power(const DiscreteDistribution& d, float u) {
  if (d.empty()) return {};
  LightChoice c;
  c.light = d.sample(u, &c.pmf);
  return c;
}

LightChoice sample_uniform(int count, float u) {
  if (count <= 0) return {};
  return {std::min(int(u * float(count)), count - 1), 1.0f / float(count)};
}

float pmf_power(const DiscreteDistribution& d, int light) { return d.empty() ? 0.0f : d.pmf(light); }
float pmf_uniform(int count) { return count > 0 ? 1.0f / float(count) : 0.0f; }

}  // namespace

// Each strategy is one visit with a lambda per member: a fourth strategy does not compile until
// all four operations handle it.
LightChoice LightSampler::sample(Vec3 p, Vec3 n, float u) const {
  if (single_ >= 0) return {single_, 1.0f};
  return std::visit(Overloaded{[&](const Power& s) { return sample_power(s.distribution, u); },
                               [&](const Uniform& s) { return sample_uniform(s.count, u); },
                               [&](const Tree& t) {
                                 return sample_tree(t, u, [&](float v) { return t.tree.sample(p, n, v); });
                               }},
                    strategy_);
}

float LightSampler::pmf(Vec3 p, Vec3 n, int light) const {
  if (single_ >= 0) return light == single_ ? 1.0f : 0.0f;
  return std::visit(Overloaded{[&](const Power& s) { return pmf_power(s.distribution, light); },
                               [&](const Uniform& s) { return pmf_uniform(s.count); },
                               [&](const Tree& t) {
                                 return pmf_tree(t, light, [&] { return t.tree.pmf(p, n, light); });
                               }},
                    strategy_);
}

LightChoice LightSampler::sample_segment(const Ray& segment, float u) const {
  if (single_ >= 0) return {single_, 1.0f};
  return std::visit(Overloaded{[&](const Power& s) { return sample_power(s.distribution, u); },
                               [&](const Uniform& s) { return sample_uniform(s.count, u); },
                               [&](const Tree& t) {
                                 return sample_tree(t, u, [&](float v) { return t.tree.sample_segment(segment, v); });
                               }},
                    strategy_);
}

float LightSampler::pmf_segment(const Ray& segment, int light) const {
  if (single_ >= 0) return light == single_ ? 1.0f : 0.0f;
  return std::visit(Overloaded{[&](const Power& s) { return pmf_power(s.distribution, light); },
                               [&](const Uniform& s) { return pmf_uniform(s.count); },
                               [&](const Tree& t) {
                                 return pmf_tree(t, light, [&] { return t.tree.pmf_segment(segment, light); });
                               }},
                    strategy_);
}

}  // namespace caligo
