// Arena: alignment, disjointness, reuse after reset, and oversized requests.
#include "core/arena.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

namespace caligo {
namespace {

struct alignas(32) Wide {
  float v[8];
};

template <typename T>
bool aligned(const T* p) {
  return reinterpret_cast<uintptr_t>(p) % alignof(T) == 0;
}

// [begin, end) address ranges of every allocation, to check that none overlap.
using Range = std::pair<uintptr_t, uintptr_t>;

template <typename T>
Range range_of(std::span<T> s) {
  const auto begin = reinterpret_cast<uintptr_t>(s.data());
  return {begin, begin + s.size_bytes()};
}

bool any_overlap(std::vector<Range> ranges) {
  std::sort(ranges.begin(), ranges.end());
  for (size_t i = 1; i < ranges.size(); ++i)
    if (ranges[i].first < ranges[i - 1].second) return true;
  return false;
}

// A mix of sizes and alignments that spills over several 256-byte blocks.
std::vector<Range> allocate_mix(Arena& arena) {
  std::vector<Range> ranges;
  for (int i = 0; i < 50; ++i) {
    auto bytes = arena.allocate<char>(size_t(1 + i % 7));
    auto doubles = arena.allocate<double>(size_t(1 + i % 3));
    auto wides = arena.allocate<Wide>(1);
    EXPECT_TRUE(aligned(doubles.data()));
    EXPECT_TRUE(aligned(wides.data()));
    ranges.push_back(range_of(bytes));
    ranges.push_back(range_of(doubles));
    ranges.push_back(range_of(wides));
  }
  return ranges;
}

}  // namespace

TEST(Arena, AllocationsAreAlignedAndDisjoint) {
  Arena arena(256);
  const std::vector<Range> ranges = allocate_mix(arena);
  EXPECT_FALSE(any_overlap(ranges));
}

TEST(Arena, MemoryIsWritable) {
  Arena arena(128);
  auto a = arena.allocate<int>(20);
  auto b = arena.allocate<int>(20);
  for (int i = 0; i < 20; ++i) {
    a[size_t(i)] = i;
    b[size_t(i)] = -i;
  }
  for (int i = 0; i < 20; ++i) {
    EXPECT_EQ(a[size_t(i)], i);
    EXPECT_EQ(b[size_t(i)], -i);
  }
}

TEST(Arena, ResetReusesMemoryWithoutGrowing) {
  Arena arena(256);
  const std::vector<Range> first = allocate_mix(arena);
  const size_t capacity = arena.capacity_bytes();
  ASSERT_GT(capacity, 0u);
  for (int round = 0; round < 5; ++round) {
    arena.reset();
    const std::vector<Range> again = allocate_mix(arena);
    EXPECT_EQ(arena.capacity_bytes(), capacity);
    EXPECT_EQ(again.front().first, first.front().first);  // starts over at the first block
    EXPECT_FALSE(any_overlap(again));
  }
}

TEST(Arena, AllocationLargerThanABlock) {
  Arena arena(64);
  auto big = arena.allocate<double>(1000);
  ASSERT_EQ(big.size(), 1000u);
  EXPECT_TRUE(aligned(big.data()));
  for (size_t i = 0; i < big.size(); ++i) big[i] = double(i);
  EXPECT_GE(arena.capacity_bytes(), 1000 * sizeof(double));
  auto small = arena.allocate<double>(4);  // goes on after the big one, in a new block
  EXPECT_FALSE(any_overlap({range_of(big), range_of(small)}));
  EXPECT_EQ(big[999], 999.0);
}

TEST(Arena, ThreadArenasGiveOneArenaPerThread) {
  ThreadArenas arenas;
  Arena& a = arenas.local();
  EXPECT_EQ(&a, &arenas.local());
}

}  // namespace caligo
