// Guided distance sampling along a marched segment (after Herholz et al. 2019, "Volume Path
// Guiding Based on Zero-Variance Random Walk Theory"): where a path scatters inside the segment is
// drawn from a one-sample mixture of the record's own density, avg sigma_s T, and that density
// times the fluence the guiding field learnt near each point, so vertices land more often where
// much light arrives (near a lamp in fog). The zero-variance density is sigma_s T times the
// in-scattered radiance; the field's fluence per spatial leaf (DirectionalTree::fluence) stands in
// for it, piecewise constant over kCells equal cells of the segment. Half the samples stay with
// the record's density, so the weight is at most 2x the unguided one and the support is the
// same: unbiased whatever the field holds.
// Grey records only (a chromatic record's hero-channel fates are sampled per channel); tracked
// segments (PathSettings::secondary through heterogeneous media) are not guided.
#pragma once

#include <array>
#include <optional>

#include "guiding/guiding_field.h"
#include "core/ray.h"
#include "raymarch/transmittance_record.h"

namespace caligo {

class GuidedDistance {
 public:
  static constexpr int kCells = 16;

  // The mixture for `record` along `ray` from `field`'s fluence, or std::nullopt where distances
  // cannot be guided (a chromatic record, no fluence learnt along the segment).
  static std::optional<GuidedDistance> along(const GuidingField& field, const Ray& ray,
                                             const TransmittanceRecord& record);

  // A scattering distance from one uniform number; its pdf is the mixture's, normalised over the
  // record like TransmittanceRecord::sample_scatter_density's. pdf_native (when given) receives
  // the record's own density at the distance.
  std::optional<DistanceSample> sample(const TransmittanceRecord& record, float u, float* pdf_native) const;
  // The mixture's density at t over the record's own (a factor in [1/2, 1/2 + kCells/2]).
  float ratio(float t) const;
  float pdf(const TransmittanceRecord& record, float t) const { return record.scatter_density_pdf(t) * ratio(t); }

 private:
  float t0_ = 0.0f, inverse_cell_ = 0.0f;
  std::array<float, kCells + 1> scatter_at_{};  // avg sigma_s T integrated to each cell's start
  std::array<float, kCells + 1> cdf_{};         // of fluence x scatter over the cells
  std::array<float, kCells> ratio_{};           // 1/2 + 1/2 fluence_k W / G
  int cell_of(float t) const;
};

}  // namespace caligo
