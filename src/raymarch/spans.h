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
  float t0, t1;          // t0 < t1; consecutive spans may touch but never overlap
  uint32_t first, count;  // primitives covering the span: span_primitives[first .. first + count)
};

// `intervals` may be in any order and may overlap; empty intervals (t1 <= t0) are ignored.
// Gaps between intervals produce no span. Primitives within a span are sorted by index.
void build_spans(std::span<const VolumeInterval> intervals, std::vector<Span>& spans,
                 std::vector<uint32_t>& span_primitives);

}  // namespace caligo
