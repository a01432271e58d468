// A sweep over sorted interval endpoints: between two consecutive distinct endpoints the set of
// covering intervals is constant, so each such stretch with a non-empty set is one span.
#include "raymarch/spans.h"

#include <algorithm>
#include <cassert>

namespace caligo {
namespace {

using Endpoint = SpanScratch::Endpoint;

void collect_endpoints(std::span<const VolumeInterval> intervals, std::vector<Endpoint>& out) {
  out.clear();
  for (uint32_t i = 0; i < intervals.size(); ++i) {
    const VolumeInterval& interval = intervals[i];
    if (!(interval.t1 > interval.t0)) continue;  // empty or NaN: covers nothing
    out.push_back({interval.t0, i, true});
    out.push_back({interval.t1, i, false});
  }
  // Order among equal t does not matter: all endpoints at one t are applied before a span is emitted.
  std::sort(out.begin(), out.end(), [](const Endpoint& a, const Endpoint& b) { return a.t < b.t; });
}

// Keeps `active` sorted by (primitive, interval index), so a span's primitives come out sorted.
void apply_endpoint(const Endpoint& e, std::span<const VolumeInterval> intervals, std::vector<uint32_t>& active) {
  const auto before = [&](uint32_t a, uint32_t b) {
    return intervals[a].primitive != intervals[b].primitive ? intervals[a].primitive < intervals[b].primitive
                                                            : a < b;
  };
  const auto it = std::lower_bound(active.begin(), active.end(), e.interval, before);
  if (e.opens) {
    active.insert(it, e.interval);
    return;
  }
  // An interval's start sorts strictly before its end, so its entry is present.
  assert(it != active.end() && *it == e.interval);
  active.erase(it);
}

// Appends [t0, t1) covered by `active`, or extends the previous span when it ends at t0 with the
// same primitives and majorant (a primitive's touching intervals would otherwise split a stretch).
void emit_span(float t0, float t1, std::span<const VolumeInterval> intervals, const std::vector<uint32_t>& active,
               std::vector<Span>& spans, std::vector<uint32_t>& span_primitives) {
  const size_t first = span_primitives.size();
  RGB sigma_maj, sigma_min;
  bool homogeneous = true;
  for (uint32_t i : active) {
    const VolumeInterval& iv = intervals[i];
    if (span_primitives.size() == first || span_primitives.back() != iv.primitive)
      span_primitives.push_back(iv.primitive);
    sigma_maj += iv.sigma_maj;
    sigma_min += iv.sigma_min;
    homogeneous = homogeneous && iv.homogeneous;
  }
  const size_t count = span_primitives.size() - first;
  if (!spans.empty()) {
    Span& last = spans.back();
    const auto last_begin = span_primitives.begin() + last.first;
    if (last.t1 == t0 && last.count == count && last.homogeneous == homogeneous &&
        last.sigma_maj == sigma_maj && last.sigma_min == sigma_min &&
        std::equal(last_begin, last_begin + count, span_primitives.begin() + first)) {
      last.t1 = t1;
      span_primitives.resize(first);
      return;
    }
  }
  spans.push_back({t0, t1, uint32_t(first), uint32_t(count), sigma_maj, homogeneous, sigma_min});
}

}  // namespace

void build_spans(std::span<const VolumeInterval> intervals, SpanScratch& scratch, std::vector<Span>& spans,
                 std::vector<uint32_t>& span_primitives) {
  spans.clear();
  span_primitives.clear();
  scratch.active.clear();
  collect_endpoints(intervals, scratch.endpoints);
  const std::vector<Endpoint>& endpoints = scratch.endpoints;
  float previous = 0.0f;
  for (size_t i = 0; i < endpoints.size();) {
    const float t = endpoints[i].t;
    // Endpoints are grouped by t, so previous < t here; an empty active set is a gap.
    if (!scratch.active.empty()) emit_span(previous, t, intervals, scratch.active, spans, span_primitives);
    for (; i < endpoints.size() && endpoints[i].t == t; ++i) apply_endpoint(endpoints[i], intervals, scratch.active);
    previous = t;
  }
}

void build_spans(std::span<const VolumeInterval> intervals, std::vector<Span>& spans,
                 std::vector<uint32_t>& span_primitives) {
  // The marcher's per-thread scratch has no slot for this, and a ray must not allocate.
  thread_local SpanScratch scratch;
  build_spans(intervals, scratch, spans, span_primitives);
}

}  // namespace caligo
