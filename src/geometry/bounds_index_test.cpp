#include "geometry/bounds_index.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "core/ray_solids.h"
#include "core/rng.h"

namespace caligo {
namespace {

TEST(BoundsIndex, FindsExactlyTheBoxesTheRayCrosses) {
  BoundsIndex index;
  Pcg32 rng(2, 9);
  std::vector<Bounds3> boxes;
  for (int i = 0; i < 300; ++i) {
    const Vec3 c(rng.next_float() * 20 - 10, rng.next_float() * 20 - 10, rng.next_float() * 20 - 10);
    const Vec3 h(0.1f + rng.next_float(), 0.1f + rng.next_float(), 0.1f + rng.next_float());
    boxes.push_back({c - h, c + h});
    EXPECT_EQ(index.add(boxes.back()), uint32_t(i));
  }
  index.commit();
  std::vector<uint32_t> found;
  for (int r = 0; r < 200; ++r) {
    const Ray ray{{rng.next_float() * 4 - 2, rng.next_float() * 4 - 2, -15},
                  normalize(Vec3(rng.next_float() - 0.5f, rng.next_float() - 0.5f, 1.0f)),
                  0.0f,
                  5.0f + 20.0f * rng.next_float()};
    index.candidates(ray, found);
    std::sort(found.begin(), found.end());
    std::vector<uint32_t> expected;
    for (uint32_t i = 0; i < boxes.size(); ++i)
      if (ray_box(ray.origin, ray.direction, boxes[i].lo, boxes[i].hi, ray.tmin, ray.tmax)) expected.push_back(i);
    EXPECT_EQ(found, expected) << "ray " << r;
  }
}

TEST(BoundsIndex, EmptyIndexAndBadBoxes) {
  BoundsIndex index;
  EXPECT_THROW(index.add(Bounds3{}), std::invalid_argument);
  index.commit();
  std::vector<uint32_t> found{7};
  index.candidates({{0, 0, 0}, {0, 0, 1}}, found);
  EXPECT_TRUE(found.empty());
}

}  // namespace
}  // namespace caligo
