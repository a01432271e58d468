#include "lights/light_sampler.h"

#include <algorithm>

#include "core/math.h"
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

// How the receiver-side rule sees a light at infinity of power phi (and the scene's diameter,
// which every light at infinity was given).
LightSampler::Infinite infinite_at_receivers(const Light& light, int index, float phi, float* diameter) {
  return std::visit(Overloaded{[&](const DirectionalLight& l) {
                                 *diameter = 2.0f * l.scene_radius;
                                 return LightSampler::Infinite{
                                     index, phi / (kPi * sqr(l.scene_radius)), -normalize(l.direction),
                                     std::sqrt(std::max(0.0f, 1.0f - sqr(l.cos_angular_radius)))};
                               },
                               [&](const EnvironmentLight& l) {
                                 *diameter = 2.0f * l.scene_radius;
                                 return LightSampler::Infinite{index, phi / (kPi * sqr(l.scene_radius)), Vec3(0.0f),
                                                               0.0f};
                               },
                               [&](const auto&) { return LightSampler::Infinite{index, 0.0f, Vec3(0.0f), 0.0f}; }},
                    light);
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
    case LightSamplerKind::kTree:
    case LightSamplerKind::kTreeFixedShare: break;
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
      t.infinite_slot[i] = int(t.infinite_at.size());
      t.infinite_at.push_back(infinite_at_receivers(lights[i], int(i), phi, &t.scene_diameter));
      infinite_weights.push_back(phi);
      infinite_power += phi;
    } else {
      finite.push_back(int(i));
      finite_power += phi;
    }
  }
  t.tree = LightTree(lights, finite);
  if (!t.infinite_at.empty()) t.infinite = DiscreteDistribution(infinite_weights);
  if (t.tree.empty())
    t.infinite_probability = t.infinite_at.empty() ? 0.0f : 1.0f;
  else if (t.infinite_at.empty())
    t.infinite_probability = 0.0f;
  else if (kind == LightSamplerKind::kTreeFixedShare)
    t.infinite_probability =
        std::clamp(infinite_power / (infinite_power + finite_power), kMinInfiniteShare, kMaxInfiniteShare);
  else
    t.infinite_probability = -1.0f;  // weighed at each receiver
  t.split = kind == LightSamplerKind::kTree;
  strategy_ = std::move(t);
}

namespace {

constexpr float kMinReceiverShare = 0.05f, kMaxReceiverShare = 0.95f;

bool is_zero(Vec3 v) { return v.x == 0.0f && v.y == 0.0f && v.z == 0.0f; }

}  // namespace

// 4 pi times the irradiance (surface) or fluence (medium) a light at infinity gives the
// receiver, integrated along a segment (see the header).
float LightSampler::infinite_importance(const Infinite& l, const Receiver& r, float diameter) {
  const float four_pi = 4.0f * kPi;
  if (r.segment) {
    const float length = std::min(r.segment->tmax - r.segment->tmin, diameter);
    return four_pi * l.fluence * std::max(length, 0.0f);
  }
  if (is_zero(r.n)) return four_pi * l.fluence;
  if (is_zero(l.towards)) return four_pi * 0.25f * l.fluence;  // an environment over a hemisphere
  return four_pi * l.fluence * std::max(0.0f, dot(r.n, l.towards) + l.sin_radius);
}

// The probability of choosing among the lights at infinity, and their total importance.
std::pair<float, float> LightSampler::infinite_share(const Tree& t, const Receiver& r) const {
  if (t.infinite_probability >= 0.0f) return {t.infinite_probability, 0.0f};
  float infinite = 0.0f;
  for (const Infinite& l : t.infinite_at) infinite += infinite_importance(l, r, t.scene_diameter);
  if (t.tree.empty()) return {1.0f, infinite};
  const float finite = r.segment ? t.tree.root_importance(*r.segment) : t.tree.root_importance(r.p, r.n);
  // Where one kind cannot light the receiver at all, the other takes every sample.
  if (!(infinite > 0.0f)) return {finite > 0.0f ? 0.0f : 0.5f, infinite};
  if (!(finite > 0.0f)) return {1.0f, infinite};
  return {std::clamp(infinite / (infinite + finite), kMinReceiverShare, kMaxReceiverShare), infinite};
}

LightChoice LightSampler::sample_tree(const Tree& t, float u, const Receiver& r) const {
  const auto [p_inf, importance] = infinite_share(t, r);
  if (u < p_inf) {
    const float v = std::min(u / p_inf, kOneMinusEpsilon);
    if (!(importance > 0.0f)) {  // the fixed share, or nothing lit: by power
      float pmf = 0.0f;
      const int k = t.infinite.sample(v, &pmf);
      return {t.infinite_at[size_t(k)].light, p_inf * pmf};
    }
    const float target = v * importance;
    float cumulative = 0.0f;
    size_t k = 0;
    float w = 0.0f;
    for (; k < t.infinite_at.size(); ++k) {
      w = infinite_importance(t.infinite_at[k], r, t.scene_diameter);
      cumulative += w;
      if (target < cumulative && w > 0.0f) break;
    }
    if (k == t.infinite_at.size()) {  // rounding at the top: the last light of positive weight
      for (k = t.infinite_at.size(); k-- > 0;)
        if ((w = infinite_importance(t.infinite_at[k], r, t.scene_diameter)) > 0.0f) break;
    }
    return {t.infinite_at[k].light, p_inf * (w / importance)};
  }
  if (t.tree.empty()) return {};
  const float v = std::min((u - p_inf) / (1.0f - p_inf), kOneMinusEpsilon);
  LightChoice c = r.segment ? t.tree.sample_segment(*r.segment, v) : t.tree.sample(r.p, r.n, v);
  c.pmf = (1.0f - p_inf) * c.pmf;
  return c;
}

float LightSampler::pmf_tree(const Tree& t, int light, const Receiver& r, bool split) const {
  if (light < 0 || size_t(light) >= t.infinite_slot.size()) return 0.0f;
  const int slot = t.infinite_slot[size_t(light)];
  const auto [p_inf, importance] = infinite_share(t, r);
  if (slot >= 0) {
    if (!(importance > 0.0f)) return p_inf * t.infinite.pmf(slot);
    return p_inf * (infinite_importance(t.infinite_at[size_t(slot)], r, t.scene_diameter) / importance);
  }
  if (t.tree.empty()) return 0.0f;
  if (split)
    return (1.0f - p_inf) *
           (r.segment ? t.tree.split_pmf_segment(*r.segment, light) : t.tree.split_pmf(r.p, r.n, light));
  return (1.0f - p_inf) * (r.segment ? t.tree.pmf_segment(*r.segment, light) : t.tree.pmf(r.p, r.n, light));
}

// The lights at infinity against the whole split tree, by one choice as in sample_tree.
LightChoices LightSampler::choose_tree(const Tree& t, float u, const Receiver& r) const {
  LightChoices out;
  const float p_inf = infinite_share(t, r).first;
  if (u < p_inf || t.tree.empty()) {
    out.add(sample_tree(t, u, r));
    return out;
  }
  const float v = std::min((u - p_inf) / (1.0f - p_inf), kOneMinusEpsilon);
  if (r.segment)
    t.tree.sample_split_segment(*r.segment, v, 1.0f - p_inf, out);
  else
    t.tree.sample_split(r.p, r.n, v, 1.0f - p_inf, out);
  return out;
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
                                 return sample_tree(t, u, Receiver{p, n});
                               }},
                    strategy_);
}

float LightSampler::pmf(Vec3 p, Vec3 n, int light) const {
  if (single_ >= 0) return light == single_ ? 1.0f : 0.0f;
  return std::visit(Overloaded{[&](const Power& s) { return pmf_power(s.distribution, light); },
                               [&](const Uniform& s) { return pmf_uniform(s.count); },
                               [&](const Tree& t) {
                                 return pmf_tree(t, light, Receiver{p, n});
                               }},
                    strategy_);
}

LightChoice LightSampler::sample_segment(const Ray& segment, float u) const {
  if (single_ >= 0) return {single_, 1.0f};
  return std::visit(Overloaded{[&](const Power& s) { return sample_power(s.distribution, u); },
                               [&](const Uniform& s) { return sample_uniform(s.count, u); },
                               [&](const Tree& t) {
                                 return sample_tree(t, u, Receiver{Vec3(0.0f), Vec3(0.0f), &segment});
                               }},
                    strategy_);
}

float LightSampler::pmf_segment(const Ray& segment, int light) const {
  if (single_ >= 0) return light == single_ ? 1.0f : 0.0f;
  return std::visit(Overloaded{[&](const Power& s) { return pmf_power(s.distribution, light); },
                               [&](const Uniform& s) { return pmf_uniform(s.count); },
                               [&](const Tree& t) {
                                 return pmf_tree(t, light, Receiver{Vec3(0.0f), Vec3(0.0f), &segment});
                               }},
                    strategy_);
}

LightChoices LightSampler::choose(Vec3 p, Vec3 n, float u) const {
  if (const auto* t = std::get_if<Tree>(&strategy_); t && t->split && single_ < 0) return choose_tree(*t, u, {p, n});
  LightChoices out;
  out.add(sample(p, n, u));
  return out;
}

float LightSampler::choice_pmf(Vec3 p, Vec3 n, int light) const {
  if (const auto* t = std::get_if<Tree>(&strategy_); t && t->split && single_ < 0)
    return pmf_tree(*t, light, {p, n}, true);
  return pmf(p, n, light);
}

LightChoices LightSampler::choose_segment(const Ray& segment, float u) const {
  if (const auto* t = std::get_if<Tree>(&strategy_); t && t->split && single_ < 0)
    return choose_tree(*t, u, {Vec3(0.0f), Vec3(0.0f), &segment});
  LightChoices out;
  out.add(sample_segment(segment, u));
  return out;
}

float LightSampler::choice_pmf_segment(const Ray& segment, int light) const {
  if (const auto* t = std::get_if<Tree>(&strategy_); t && t->split && single_ < 0)
    return pmf_tree(*t, light, {Vec3(0.0f), Vec3(0.0f), &segment}, true);
  return pmf_segment(segment, light);
}

}  // namespace caligo
