// Splits overlapping volume intervals into disjoint spans sorted along the ray, each listing
// every primitive that covers it (the seed's "segments split into disjoint sorted spans").
// Buffers are passed in and reused so a ray does not allocate once they have grown.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "volumes/interval.h"

namespace caligo {

struct Span {
  float t0, t1;           // t0 < t1; consecutive spans may touch but never overlap
  uint32_t first, count;  // primitives covering the span: span_primitives[first .. first + count)
};

// Working memory of build_spans, kept by the caller (one per thread) so that building spans
// does not allocate once its vectors have grown.
struct SpanScratch {
  struct Endpoint {
    float t;
    uint32_t primitive;
    bool opens;  // an interval's start (true) or end (false)
  };
  std::vector<Endpoint> endpoints;  // every non-empty interval's two ends, sorted by t
  std::vector<uint32_t> active;     // primitives covering the sweep position, sorted, with repeats
};

// `intervals` may be in any order and may overlap; empty intervals (t1 <= t0, or NaN) are ignored.
// Gaps between intervals produce no span. Primitives within a span are sorted by index and listed
// once even if several of their intervals cover it. Touching spans always differ in their
// primitives: where they would not (a primitive's intervals that touch) they are merged.
// O(n log n + output size) for n intervals.
void build_spans(std::span<const VolumeInterval> intervals, SpanScratch& scratch, std::vector<Span>& spans,
                 std::vector<uint32_t>& span_primitives);
// The same with a thread_local scratch (still allocation-free per ray once it has grown).
void build_spans(std::span<const VolumeInterval> intervals, std::vector<Span>& spans,
                 std::vector<uint32_t>& span_primitives);

}  // namespace caligo
