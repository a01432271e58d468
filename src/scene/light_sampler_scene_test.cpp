// The scene's light samplers (Scene::light_sampler): `power` is the former selection bit for bit
// (so --light-sampler power reproduces earlier images), on every built-in scene with lights;
// the tree's pmfs sum to one on the many-lamps town.
#include <gtest/gtest.h>

#include "core/rng.h"
#include "scene/builtins.h"
#include "scene/scene.h"

namespace caligo {
namespace {

float power_of(const Light& light) { return power(light); }

TEST(SceneLightSampler, PowerIsTheOldSelectionOnEveryBuiltin) {
  int scenes = 0;
  // The built-ins with lights of every kind (the grid and big-mesh scenes add nothing here).
  for (const char* name : {"default", "point-in-sphere", "lights-showcase", "lamp-in-fog", "spot-shafts", "many-lamps",
                           "underwater", "sss", "wyman-20k-spot"}) {
    const BuiltinScene* b = find_builtin(name);
    ASSERT_NE(b, nullptr) << name;
    const auto scene = Scene::build(parse_builtin(*b));
    const LightSampler& power = scene->light_sampler(LightSamplerKind::kPower);
    const int n = int(scene->lights().size());
    // The former selection: one distribution over max(0, power) of the scene's lights.
    std::vector<float> weights;
    float total = 0.0f;
    for (const Light& light : scene->lights()) total += weights.emplace_back(std::max(0.0f, power_of(light)));
    const DiscreteDistribution former = total > 0.0f ? DiscreteDistribution(weights) : DiscreteDistribution();
    const auto former_pmf = [&](int i) { return former.empty() ? 0.0f : former.pmf(i); };
    for (int i = 0; i < n; ++i) {
      ASSERT_EQ(power.pmf({1, 2, 3}, {0, 1, 0}, i), former_pmf(i)) << name << " light " << i;
      ASSERT_EQ(power.pmf_segment(Ray{{0, 0, 0}, {1, 0, 0}, 0, 5}, i), former_pmf(i)) << name;
    }
    Pcg32 rng(1, uint64_t(scenes));
    for (int k = 0; k < 1000 && n > 0; ++k) {
      const float u = rng.next_float();
      float old_pmf = 0.0f;
      const int old = former.empty() ? -1 : former.sample(u, &old_pmf);
      const LightChoice c = power.sample({}, {}, u);
      ASSERT_EQ(c.light, old) << name;
      if (old >= 0) {
        ASSERT_EQ(c.pmf, old_pmf) << name;
      }
    }
    ++scenes;
  }
  EXPECT_EQ(scenes, 9);
}

// Where spot cones cut off a whole subtree (a node may reach a point its children's cones do
// not), sample() chooses nothing with the remaining probability: the pmfs sum to at most one,
// and on the street (not inside a building) most of the choice is spent on lights.
TEST(SceneLightSampler, ManyLampsHasAThousandLightsAndTheTreeSpendsMostChoicesOnLights) {
  const auto scene = Scene::build(parse_builtin(*find_builtin("many-lamps")));
  int finite = 0;
  for (const Light& l : scene->lights()) finite += is_infinite(l) ? 0 : 1;
  EXPECT_EQ(finite, 1000);
  const LightSampler& tree = scene->light_sampler(LightSamplerKind::kTree);
  for (Vec3 p : {Vec3(0, 0.01f, -20), Vec3(-30, 3, -100), Vec3(2, 8, -50)}) {
    double sum = 0.0;
    for (int i = 0; i < int(scene->lights().size()); ++i) sum += tree.pmf(p, {}, i);
    EXPECT_LE(sum, 1.0 + 1e-5);
    EXPECT_GT(sum, 0.9) << p.x << " " << p.y << " " << p.z;
  }
}

}  // namespace
}  // namespace caligo
