#include "integrators/guided_distance.h"

#include <algorithm>
#include <cmath>

namespace caligo {

std::optional<GuidedDistance> GuidedDistance::along(const GuidingField& field, const Ray& ray,
                                                    const TransmittanceRecord& record) {
  if (!record.grey() || record.empty()) return std::nullopt;
  const float total = record.scatter_weight_total();
  const float t0 = record.t_begin(), length = record.t_end() - t0;
  if (!(total > 0.0f) || !(length > 0.0f) || !std::isfinite(length)) return std::nullopt;
  GuidedDistance g;
  g.t0_ = t0;
  g.inverse_cell_ = float(kCells) / length;
  // Grey: every channel's integral is the average's.
  for (int k = 0; k <= kCells; ++k)
    g.scatter_at_[size_t(k)] = k == kCells ? total : record.scatter_up_to_grey(t0 + length * float(k) / kCells);
  double guided = 0.0;
  std::array<double, kCells> mass{};
  Bounds3 leaf{Vec3(1.0f), Vec3(0.0f)};  // empty: the first midpoint looks its leaf up
  float fluence = 0.0f;
  for (int k = 0; k < kCells; ++k) {
    const float w = std::max(0.0f, g.scatter_at_[size_t(k) + 1] - g.scatter_at_[size_t(k)]);
    const Vec3 mid = ray.at(t0 + length * (float(k) + 0.5f) / kCells);
    if (w > 0.0f && !leaf.contains(mid)) fluence = field.fluence(mid, &leaf);
    mass[size_t(k)] = w > 0.0f ? double(w) * fluence : 0.0;
    guided += mass[size_t(k)];
  }
  if (!(guided > 0.0) || !std::isfinite(guided)) return std::nullopt;
  double cumulative = 0.0;
  int last = 0;  // the last cell with guided mass
  for (int k = 0; k < kCells; ++k) {
    if (mass[size_t(k)] > 0.0) last = k;
    const float w = g.scatter_at_[size_t(k) + 1] - g.scatter_at_[size_t(k)];
    // The guided density over the record's is fluence_k x total / guided inside cell k.
    g.ratio_[size_t(k)] = w > 0.0f ? 0.5f + 0.5f * float(mass[size_t(k)] * total / (double(w) * guided)) : 0.5f;
    cumulative += mass[size_t(k)] / guided;
    g.cdf_[size_t(k) + 1] = float(cumulative);
  }
  // Cells after the last with mass end at exactly 1, so no rounding slice of u reaches them.
  for (int k = last + 1; k <= kCells; ++k) g.cdf_[size_t(k)] = 1.0f;
  return g;
}

int GuidedDistance::cell_of(float t) const {
  return std::clamp(int((t - t0_) * inverse_cell_), 0, kCells - 1);
}

float GuidedDistance::ratio(float t) const { return ratio_[size_t(cell_of(t))]; }

std::optional<DistanceSample> GuidedDistance::sample(const TransmittanceRecord& record, float u,
                                                     float* pdf_native) const {
  const float total = record.scatter_weight_total();
  float fraction;  // of the record's scatter integral below the sampled point
  if (u < 0.5f) {
    fraction = 2.0f * u;
  } else {
    const float v = std::min(2.0f * u - 1.0f, 0x1.fffffep-1f);
    const int k = int(std::upper_bound(cdf_.begin() + 1, cdf_.end() - 1, v) - (cdf_.begin() + 1));
    const float within = (v - cdf_[size_t(k)]) / std::max(cdf_[size_t(k) + 1] - cdf_[size_t(k)], 1e-30f);
    const float lo = scatter_at_[size_t(k)], hi = scatter_at_[size_t(k) + 1];
    fraction = (lo + std::clamp(within, 0.0f, 1.0f) * (hi - lo)) / total;
  }
  auto s = record.sample_scatter_channel(0, std::clamp(fraction, 0.0f, 0x1.fffffep-1f));
  if (!s) return std::nullopt;
  if (pdf_native) *pdf_native = s->pdf;
  s->pdf *= ratio(s->t);
  return s;
}

}  // namespace caligo
