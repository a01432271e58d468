// Splits overlapping volume intervals into disjoint spans sorted along the ray, each listing
// every primitive that covers it (the seed's "segments split into disjoint sorted spans")
// with the sum of their majorants.
// Buffers are passed in and reused so a ray does not allocate once they have grown.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/rgb.h"
#include "volumes/interval.h"

namespace caligo {

struct Span {
  float t0, t1;           // t0 < t1; consecutive spans may touch but never overlap
  uint32_t first, count;  // primitives covering the span: span_primitives[first .. first + count)
  RGB sigma_maj;          // sum of the covering intervals' majorants: bounds sigma_t on the span
  bool homogeneous;       // every covering interval is homogeneous
  RGB sigma_min{};        // sum of the covering intervals' minima: below sigma_t on the span
};

// Working memory of build_spans, kept by the caller (one per thread) so that building spans
// does not allocate once its vectors have grown.
struct SpanScratch {
  struct Endpoint {
    float t;
    uint32_t interval;  // index into the intervals
    bool opens;         // an interval's start (true) or end (false)
  };
  std::vector<Endpoint> endpoints;  // every non-empty interval's two ends, sorted by t
  std::vector<uint32_t> active;     // intervals covering the sweep position, by (primitive, index)
};

// `intervals` may be in any order and may overlap; empty intervals (t1 <= t0, or NaN) are ignored.
// Gaps between intervals produce no span. Primitives within a span are sorted by index and listed
// once even if several of their intervals cover it. Touching spans always differ in their
// primitives, majorant or homogeneity: where they would not (a primitive's intervals that touch
// with equal majorants) they are merged; intervals with different majorants stay apart, so
// delta tracking and marching see each majorant where it holds.
// O(n log n + output size) for n intervals.
void build_spans(std::span<const VolumeInterval> intervals, SpanScratch& scratch, std::vector<Span>& spans,
                 std::vector<uint32_t>& span_primitives);
// The same with a thread_local scratch (still allocation-free per ray once it has grown).
void build_spans(std::span<const VolumeInterval> intervals, std::vector<Span>& spans,
                 std::vector<uint32_t>& span_primitives);

}  // namespace caligo
