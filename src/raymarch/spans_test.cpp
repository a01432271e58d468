// Tests of build_spans: hand-made configurations with known answers, and random interval sets
// checked point by point against a brute-force scan of the intervals.
#include "raymarch/spans.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include "core/rng.h"

namespace caligo {
namespace {

struct ExpectedSpan {
  float t0, t1;
  std::vector<uint32_t> primitives;
};

struct Built {
  std::vector<Span> spans;
  std::vector<uint32_t> primitives;

  std::vector<uint32_t> primitives_of(const Span& s) const {
    return {primitives.begin() + s.first, primitives.begin() + s.first + s.count};
  }
};

Built build(const std::vector<VolumeInterval>& intervals) {
  Built b;
  build_spans(intervals, b.spans, b.primitives);
  return b;
}

void expect_spans(const Built& b, const std::vector<ExpectedSpan>& expected) {
  ASSERT_EQ(b.spans.size(), expected.size());
  for (size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(b.spans[i].t0, expected[i].t0) << "span " << i;
    EXPECT_EQ(b.spans[i].t1, expected[i].t1) << "span " << i;
    EXPECT_EQ(b.primitives_of(b.spans[i]), expected[i].primitives) << "span " << i;
  }
}

TEST(BuildSpans, EmptyInputGivesNoSpans) {
  std::vector<Span> spans{{0, 1, 0, 0}};
  std::vector<uint32_t> primitives{7};
  build_spans({}, spans, primitives);
  EXPECT_TRUE(spans.empty());
  EXPECT_TRUE(primitives.empty());
}

TEST(BuildSpans, SingleInterval) { expect_spans(build({{1, 2, 5}}), {{1, 2, {5}}}); }

TEST(BuildSpans, DisjointIntervalsLeaveAGap) {
  expect_spans(build({{2, 3, 1}, {0, 1, 0}}), {{0, 1, {0}}, {2, 3, {1}}});
}

TEST(BuildSpans, NestedIntervals) {
  expect_spans(build({{2, 4, 1}, {0, 10, 0}}), {{0, 2, {0}}, {2, 4, {0, 1}}, {4, 10, {0}}});
}

TEST(BuildSpans, OverlappingIntervalsListPrimitivesByIndex) {
  expect_spans(build({{0, 5, 2}, {3, 8, 1}}), {{0, 3, {2}}, {3, 5, {1, 2}}, {5, 8, {1}}});
}

TEST(BuildSpans, IdenticalIntervalsShareOneSpan) {
  expect_spans(build({{1, 2, 3}, {1, 2, 1}, {1, 2, 2}}), {{1, 2, {1, 2, 3}}});
}

TEST(BuildSpans, TouchingIntervalsOfDifferentPrimitivesStaySeparate) {
  expect_spans(build({{1, 2, 1}, {0, 1, 0}}), {{0, 1, {0}}, {1, 2, {1}}});
}

TEST(BuildSpans, TouchingIntervalsOfOnePrimitiveMerge) {
  expect_spans(build({{1, 2, 4}, {0, 1, 4}}), {{0, 2, {4}}});
}

TEST(BuildSpans, OverlappingIntervalsOfOnePrimitiveListItOnce) {
  expect_spans(build({{0, 2, 3}, {1, 3, 3}, {1.5f, 2.5f, 0}}),
               {{0, 1.5f, {3}}, {1.5f, 2.5f, {0, 3}}, {2.5f, 3, {3}}});
}

TEST(BuildSpans, EmptyAndNanIntervalsAreIgnored) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  expect_spans(build({{1, 1, 0}, {3, 2, 1}, {nan, 2, 2}, {0, nan, 3}, {5, 6, 4}}), {{5, 6, {4}}});
}

TEST(BuildSpans, InfiniteEndIsKept) {
  const float inf = std::numeric_limits<float>::infinity();
  expect_spans(build({{0, inf, 0}, {1, 2, 1}}), {{0, 1, {0}}, {1, 2, {0, 1}}, {2, inf, {0}}});
}

TEST(BuildSpans, DoesNotAllocateOnceGrown) {
  const std::vector<VolumeInterval> intervals{{0, 4, 2}, {1, 3, 0}, {2, 5, 1}, {6, 7, 0}};
  SpanScratch scratch;
  std::vector<Span> spans;
  std::vector<uint32_t> primitives;
  build_spans(intervals, scratch, spans, primitives);
  const void* pointers[4] = {spans.data(), primitives.data(), scratch.endpoints.data(),
                             scratch.active.data()};
  build_spans(intervals, scratch, spans, primitives);
  EXPECT_EQ(pointers[0], spans.data());
  EXPECT_EQ(pointers[1], primitives.data());
  EXPECT_EQ(pointers[2], scratch.endpoints.data());
  EXPECT_EQ(pointers[3], scratch.active.data());
}

// ---- Random interval sets against brute force ------------------------------------------------

// Endpoints on a coarse grid half the time, so ties, touching and identical intervals are common.
std::vector<VolumeInterval> random_intervals(Pcg32& rng) {
  const int n = int(rng.next_u32() % 16);
  const bool grid = rng.next_u32() % 2 == 0;
  std::vector<VolumeInterval> out;
  for (int i = 0; i < n; ++i) {
    float a = 10.0f * rng.next_float(), b = 10.0f * rng.next_float();
    if (grid) a = std::floor(a), b = std::floor(b);
    if (rng.next_u32() % 8 != 0) {  // mostly well-formed, sometimes reversed or empty
      if (b < a) std::swap(a, b);
    }
    out.push_back({a, b, rng.next_u32() % 6});
  }
  return out;
}

std::vector<uint32_t> covering_brute_force(const std::vector<VolumeInterval>& intervals, float t) {
  std::vector<uint32_t> out;
  for (const VolumeInterval& iv : intervals)
    if (iv.t0 <= t && t < iv.t1) out.push_back(iv.primitive);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

void expect_well_formed(const Built& b) {
  for (size_t i = 0; i < b.spans.size(); ++i) {
    const Span& s = b.spans[i];
    EXPECT_LT(s.t0, s.t1);
    ASSERT_LE(size_t(s.first) + s.count, b.primitives.size());
    EXPECT_GT(s.count, 0u);
    const std::vector<uint32_t> p = b.primitives_of(s);
    EXPECT_TRUE(std::adjacent_find(p.begin(), p.end(), std::greater_equal<>()) == p.end())
        << "not strictly sorted";
    if (i == 0) continue;
    const Span& prev = b.spans[i - 1];
    EXPECT_LE(prev.t1, s.t0);
    if (prev.t1 == s.t0) {
      EXPECT_NE(b.primitives_of(prev), p) << "touching spans with equal sets not merged";
    }
  }
}

TEST(BuildSpans, MatchesBruteForceOnRandomIntervals) {
  Pcg32 rng(42, 7);
  SpanScratch scratch;
  Built b;
  for (int trial = 0; trial < 400; ++trial) {
    const std::vector<VolumeInterval> intervals = random_intervals(rng);
    build_spans(intervals, scratch, b.spans, b.primitives);
    expect_well_formed(b);
    std::vector<float> probes;
    for (int i = 0; i < 64; ++i) probes.push_back(-1.0f + 12.0f * rng.next_float());
    for (const VolumeInterval& iv : intervals) probes.insert(probes.end(), {iv.t0, iv.t1});  // boundaries too
    for (float t : probes) {
      const auto span =
          std::find_if(b.spans.begin(), b.spans.end(), [t](const Span& s) { return s.t0 <= t && t < s.t1; });
      const std::vector<uint32_t> expected = covering_brute_force(intervals, t);
      if (span == b.spans.end()) {
        EXPECT_TRUE(expected.empty()) << "t = " << t << " covered but in no span (trial " << trial << ")";
      } else {
        EXPECT_EQ(b.primitives_of(*span), expected) << "t = " << t << " (trial " << trial << ")";
      }
    }
    if (HasFailure()) return;
  }
}

}  // namespace
}  // namespace caligo

namespace caligo {
namespace {

// A grid primitive's touching intervals with different majorants stay apart (delta tracking
// and step placement need each bound where it holds); equal ones merge.
TEST(BuildSpans, TouchingIntervalsMergeOnlyWithEqualMajorants) {
  std::vector<Span> spans;
  std::vector<uint32_t> prims;
  build_spans(std::vector<VolumeInterval>{{0, 1, 3, RGB(2.0f), false}, {1, 2, 3, RGB(5.0f), false},
                                          {2, 3, 3, RGB(5.0f), false}},
              spans, prims);
  ASSERT_EQ(spans.size(), 2u);
  EXPECT_EQ(spans[0].t1, 1.0f);
  EXPECT_EQ(spans[0].sigma_maj.r, 2.0f);
  EXPECT_EQ(spans[1].t0, 1.0f);
  EXPECT_EQ(spans[1].t1, 3.0f);
  EXPECT_EQ(spans[1].sigma_maj.g, 5.0f);
}

// Overlapping primitives add their majorants; a span is homogeneous only if all of its
// intervals are.
TEST(BuildSpans, OverlapsSumMajorantsAndAndHomogeneity) {
  std::vector<Span> spans;
  std::vector<uint32_t> prims;
  build_spans(std::vector<VolumeInterval>{{0, 2, 0, RGB(1.0f, 2.0f, 3.0f), true},
                                          {1, 3, 1, RGB(0.5f), false}},
              spans, prims);
  ASSERT_EQ(spans.size(), 3u);
  EXPECT_TRUE(spans[0].homogeneous);
  EXPECT_EQ(spans[0].sigma_maj.b, 3.0f);
  EXPECT_FALSE(spans[1].homogeneous);
  EXPECT_EQ(spans[1].sigma_maj.r, 1.5f);
  EXPECT_EQ(spans[1].sigma_maj.b, 3.5f);
  EXPECT_EQ(spans[1].count, 2u);
  EXPECT_FALSE(spans[2].homogeneous);
  EXPECT_EQ(spans[2].sigma_maj.g, 0.5f);
}

}  // namespace
}  // namespace caligo
