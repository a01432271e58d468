#include "media/medium_stack.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace caligo {
namespace {

MediumEntry object(uint32_t id, int priority, int medium, float ior = 1.0f) { return {id, priority, {medium, ior}}; }

// The seed's two overlapping cubes, red (0) and green (1), along a ray that enters red, enters
// green, leaves red, leaves green: what is seen and which medium each stretch is in.
struct CubeRun {
  bool seen[4];
  int medium[4];  // after each crossing
};

CubeRun cubes(int red_priority, int green_priority) {
  MediumStack stack;
  const MediumEntry red = object(0, red_priority, 0), green = object(1, green_priority, 1);
  CubeRun run{};
  const MediumEntry order[4] = {red, green, red, green};
  for (int i = 0; i < 4; ++i) {
    const auto c = stack.cross(order[i]);
    run.seen[i] = c.real;
    run.medium[i] = c.after.medium;
  }
  EXPECT_TRUE(stack.empty());
  return run;
}

TEST(MediumStack, RedHigherIsSeenInsideGreenAndHidesGreen) {
  const CubeRun r = cubes(kPriorityHigh, kPriorityNormal);
  // Entering red: seen. Entering green inside red: hidden. Leaving red inside green: seen (the
  // red cube's face is visible inside green). Leaving green: seen.
  EXPECT_TRUE(r.seen[0]);
  EXPECT_FALSE(r.seen[1]);
  EXPECT_TRUE(r.seen[2]);
  EXPECT_TRUE(r.seen[3]);
  EXPECT_EQ(r.medium[0], 0);
  EXPECT_EQ(r.medium[1], 0);  // the overlap is red
  EXPECT_EQ(r.medium[2], 1);
  EXPECT_EQ(r.medium[3], -1);
}

TEST(MediumStack, GreenHigherHidesRedInsideIt) {
  const CubeRun r = cubes(kPriorityNormal, kPriorityHigh);
  EXPECT_TRUE(r.seen[0]);
  EXPECT_TRUE(r.seen[1]);   // green's face inside red
  EXPECT_FALSE(r.seen[2]);  // red's far face inside green: invisible
  EXPECT_TRUE(r.seen[3]);
  EXPECT_EQ(r.medium[1], 1);  // the overlap is green
  EXPECT_EQ(r.medium[2], 1);
}

TEST(MediumStack, EqualPrioritiesMergeAndKeepTheMediumBeingLeft) {
  const CubeRun r = cubes(kPriorityNormal, kPriorityNormal);
  EXPECT_TRUE(r.seen[0]);
  EXPECT_FALSE(r.seen[1]);  // no interior hits
  EXPECT_FALSE(r.seen[2]);
  EXPECT_TRUE(r.seen[3]);
  // Red was entered first: its medium carries through the overlap and on into green alone.
  EXPECT_EQ(r.medium[1], 0);
  EXPECT_EQ(r.medium[2], 0);
  EXPECT_EQ(r.medium[3], -1);
}

TEST(MediumStack, LiquidOverlappingGlassRefractsGlassToLiquid) {
  // Glass (higher priority, 1.5) around a liquid (1.33) modelled slightly overlapping it: a ray
  // enters the glass wall, enters the liquid inside the wall (hidden), leaves the wall into the
  // liquid (seen: 1.5 -> 1.33), and leaves through the liquid's free surface (1.33 -> 1).
  MediumStack stack;
  const MediumEntry glass = object(7, kPriorityHigh, 0, 1.5f), liquid = object(9, kPriorityNormal, 1, 1.33f);
  auto c = stack.cross(glass);  // air -> glass
  EXPECT_TRUE(c.real);
  EXPECT_FLOAT_EQ(c.before.ior, 1.0f);
  EXPECT_FLOAT_EQ(c.after.ior, 1.5f);
  c = stack.cross(liquid);  // inside the wall: hidden
  EXPECT_FALSE(c.real);
  c = stack.cross(glass);  // the wall's inner face: glass -> liquid, no air gap
  EXPECT_TRUE(c.real);
  EXPECT_FLOAT_EQ(c.before.ior, 1.5f);
  EXPECT_FLOAT_EQ(c.after.ior, 1.33f);
  // Out through the liquid's free surface (no glass there): liquid -> air.
  c = stack.cross(liquid);
  EXPECT_TRUE(c.real);
  EXPECT_FLOAT_EQ(c.before.ior, 1.33f);
  EXPECT_FLOAT_EQ(c.after.ior, 1.0f);
  EXPECT_TRUE(stack.empty());
}

TEST(MediumStack, HighPriorityEmptyBoxClipsWater) {
  // A clipping box (very high, vacuum) around a camera under water: water crossings inside the
  // box are hidden, leaving the box below the water line puts the ray in water.
  MediumStack stack;
  const MediumEntry water = object(1, kPriorityNormal, 3, 1.33f), clip = object(2, kPriorityVeryHigh, -1);
  stack.cross(water);
  stack.cross(clip);
  EXPECT_EQ(stack.current().medium, -1);
  EXPECT_FALSE(stack.cross(water).real);  // the surface, seen from inside the box: hidden
  EXPECT_EQ(stack.current().medium, -1);
  const auto leave = stack.cross(clip);   // out of the box above the water: air
  EXPECT_TRUE(leave.real);
  EXPECT_EQ(leave.after.medium, -1);
  MediumStack below;
  below.cross(water);
  below.cross(clip);
  EXPECT_EQ(below.cross(clip).after.medium, 3);  // out of the box below the water line: water
}

// Random overlapping spheres with random priorities; rays through all of them. The stack holds
// exactly the spheres containing the ray and ends empty; between crossings the medium comes from
// an object of the highest containing priority (vacuum when nothing contains the ray; merged
// equal priorities may keep a medium whose object the ray has left); a crossing is seen exactly when the crossed
// object's priority is strictly above every other object's on the stack.
TEST(MediumStack, RandomRaysThroughOverlappingSpheresStayBalancedAndFollowThePriorities) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const int levels[] = {kPriorityVeryHigh, kPriorityHigh, kPriorityNormal, kPriorityLow, kPriorityVeryLow};
  MediumStack stack;
  size_t max_depth = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    struct Ball {
      float c[3], r;
      int priority;
    };
    std::vector<Ball> balls(size_t(1 + trial % 16));
    for (Ball& b : balls) {
      for (float& x : b.c) x = u(rng);
      b.r = 0.3f + 0.7f * std::abs(u(rng));
      b.priority = levels[rng() % 5];
    }
    float o[3], d[3];
    for (int k = 0; k < 3; ++k) o[k] = 4.0f * u(rng);
    float n = 0;
    for (int k = 0; k < 3; ++k) {
      d[k] = u(rng);
      n += d[k] * d[k];
    }
    for (float& x : d) x /= std::sqrt(n);
    struct Hit {
      float t;
      uint32_t ball;
    };
    std::vector<Hit> hits;
    for (uint32_t i = 0; i < balls.size(); ++i) {
      float oc[3], b = 0, c = -balls[i].r * balls[i].r;
      for (int k = 0; k < 3; ++k) {
        oc[k] = o[k] - balls[i].c[k];
        b += oc[k] * d[k];
        c += oc[k] * oc[k];
      }
      const float disc = b * b - c;
      if (!(disc > 0.0f)) continue;
      const float s = std::sqrt(disc);
      if (-b - s > 0.0f) hits.push_back({-b - s, i});  // the ray starts outside every sphere:
      if (-b + s > 0.0f) hits.push_back({-b + s, i});  // filter rays that start inside below
    }
    bool starts_inside = false;
    for (const Ball& b : balls) {
      float q = 0;
      for (int k = 0; k < 3; ++k) q += (o[k] - b.c[k]) * (o[k] - b.c[k]);
      starts_inside |= q < b.r * b.r;
    }
    if (starts_inside) continue;
    std::sort(hits.begin(), hits.end(), [](const Hit& a, const Hit& b) { return a.t < b.t; });
    stack.clear();
    for (size_t h = 0; h < hits.size(); ++h) {
      const Ball& x = balls[hits[h].ball];
      const int top_before = stack.empty() ? 1 << 30 : [&] {
        int best = 1 << 30;
        for (const MediumEntry& e : stack.entries()) best = std::min(best, e.priority);
        return best;
      }();
      const auto c = stack.cross(object(hits[h].ball, x.priority, int(hits[h].ball)));
      max_depth = std::max(max_depth, stack.size());
      // Containing set just after this crossing, geometrically.
      const float t_mid = h + 1 < hits.size() ? 0.5f * (hits[h].t + hits[h + 1].t) : hits[h].t + 1.0f;
      int best = 1 << 30;
      std::vector<int> best_set;
      for (uint32_t i = 0; i < balls.size(); ++i) {
        float q = 0;
        for (int k = 0; k < 3; ++k) {
          const float p = o[k] + d[k] * t_mid - balls[i].c[k];
          q += p * p;
        }
        if (q < balls[i].r * balls[i].r) {
          if (balls[i].priority < best) best = balls[i].priority, best_set.clear();
          if (balls[i].priority == best) best_set.push_back(int(i));
        }
      }
      ASSERT_EQ(stack.size(), [&] {
        size_t inside = 0;
        for (uint32_t i = 0; i < balls.size(); ++i) {
          float q = 0;
          for (int k = 0; k < 3; ++k) {
            const float p = o[k] + d[k] * t_mid - balls[i].c[k];
            q += p * p;
          }
          inside += q < balls[i].r * balls[i].r;
        }
        return inside;
      }()) << "trial " << trial;
      // Ties keep the medium of the object being left (merging), which may no longer contain
      // the point: the medium must come from an object of the highest containing priority.
      if (best_set.empty()) {
        EXPECT_EQ(stack.current().medium, -1);
      } else {
        ASSERT_GE(stack.current().medium, 0) << "trial " << trial << " hit " << h;
        EXPECT_EQ(balls[size_t(stack.current().medium)].priority, best) << "trial " << trial << " hit " << h;
      }
      // Seen exactly when the crossed object is strictly above everything else on the stack.
      const int others = c.entering ? top_before : [&] {
        int b2 = 1 << 30;
        for (const MediumEntry& e : stack.entries()) b2 = std::min(b2, e.priority);
        return b2;
      }();
      EXPECT_EQ(c.real, x.priority < others) << "trial " << trial << " hit " << h;
    }
    EXPECT_TRUE(stack.empty()) << "trial " << trial;
  }
  EXPECT_GE(max_depth, 5u);  // deep enough nesting was exercised (fixed seed)
}

}  // namespace
}  // namespace caligo
