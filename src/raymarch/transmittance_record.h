// The TransmittanceRecord of decoupled ray marching (Kulla & Fajardo 2012; the seed's "Ray
// Marching" part): the march of one ray segment stored front to back as steps of constant
// coefficients, so that transmittance at any t is a piecewise exponential found by binary
// search, and distances can be sampled from it for any number of light samples without
// marching again.
//
// Chromatic media: each channel has its own exponential. Distance sampling picks a channel
// and inverts its exponential exactly; the reported pdf is the average over the channels
// (one-sample MIS over channels), so estimates stay unbiased for any colour of sigma.
//
// Memory: steps and lobes live in vectors that clear() keeps, so a per-thread record does
// not allocate once it has grown.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "core/rgb.h"
#include "media/phase.h"

namespace caligo {

// One term of the phase-function mixture at a step. The weight is that primitive's share of
// sigma_s in each colour channel: where differently coloured media overlap, each channel
// scatters with its own mixture.
struct PhaseLobe {
  RGB weight;
  PhaseFunction phase;
};

struct MarchStep {
  float t0, t1;          // [t0, t1), steps sorted by t and disjoint; gaps between them are vacuum
  RGB sigma_t, sigma_s;  // constant over the step, 1/m
  RGB transmittance;     // T(t0): from the record's start to the start of this step
  RGB scatter_before;    // integral of sigma_s(t) T(t) dt from the start to t0, per channel
  uint32_t first_lobe, lobe_count;
};

// A partly transparent surface the march met (materials/opacity_map.h): at t the transmittance
// of every channel drops by the factor 1 - opacity. `before` is T just in front of it.
struct SurfaceLayer {
  float t;
  float opacity;
  RGB before;
};

struct DistanceSample {
  float t;
  float pdf;       // per unit length (see the sampling functions for its normalisation); a probability for a layer
  int step;        // index of the step containing t
  int layer = -1;  // free flight and fates only: the surface layer the path meets instead (t is its)
};

class TransmittanceRecord {
 public:
  // Empties the record (keeping its memory).
  void clear();
  // Appends [t0, t1) with constant coefficients; t0 must be >= the previous step's t1 and
  // t1 > t0. Lobe weights should sum to 1 in every channel with sigma_s > 0.
  void push(float t0, float t1, RGB sigma_t, RGB sigma_s, std::span<const PhaseLobe> lobes);
  // Partly transparent surfaces along the ray, sorted by t (their `before` is ignored), after the
  // march has pushed its steps: each layer becomes a step boundary (a step it falls inside is split;
  // one in a gap or past the end starts a step of vacuum) where T drops by 1 - opacity, so every
  // query and sampler below sees it. The layers' masses opacity x T in front are layer_totals().
  void insert_layers(std::span<const SurfaceLayer> layers);
  std::span<const SurfaceLayer> layers() const { return layers_; }
  // Per channel, the sum over layers of opacity x T in front: the probability of meeting each.
  RGB layer_totals() const { return layer_totals_; }
  // A layer chosen with probability opacity x T_c in front / layer_totals()[c] (c < 0: by the
  // channel average); its pdf is that probability. std::nullopt when no layer has mass.
  std::optional<DistanceSample> sample_layer(int c, float u) const;

  // Adds emitted radiance already integrated by the marcher (for the record's owner to read).
  void add_emission(RGB radiance) { emission_ += radiance; }
  // Adds the integral of sigma_h T over a step, already integrated by the marcher: the share of
  // the ray's view that holdout media take (channel average).
  void add_holdout(float amount) { holdout_ += amount; }

  bool empty() const { return steps_.empty(); }
  // Every step's sigma_t and sigma_s are grey (equal in all channels): the channel a sampler
  // picks does not change the distance it returns.
  bool grey() const { return grey_; }
  std::span<const MarchStep> steps() const { return steps_; }
  std::span<const PhaseLobe> lobes(const MarchStep& step) const;
  RGB emission() const { return emission_; }
  float holdout_total() const { return holdout_; }
  float t_begin() const;  // start of the first step (0 when empty)
  float t_end() const;    // end of the last step (0 when empty)

  // Index of the step containing t, or -1 in a gap or outside the record.
  int find_step(float t) const;
  // Transmittance from the record's start to t (1 before the first step, transmittance_end()
  // after the last).
  RGB transmittance(float t) const;
  RGB transmittance_end() const;

  // Density sampling for next-event estimation: t with pdf proportional to
  // avg_c sigma_s,c(t) T_c(t), normalised over the record (always returns a point inside a
  // step when the record scatters at all; std::nullopt when sigma_s is zero everywhere).
  // u_channel picks the channel, u_distance the distance.
  std::optional<DistanceSample> sample_scatter_density(float u_channel, float u_distance) const;
  float scatter_density_pdf(float t) const;
  // avg_c of the integral of sigma_s,c T_c over the whole record.
  float scatter_weight_total() const;
  // The integral of sigma_s T from the record's start to t in the first channel (all of it in a
  // grey record).
  float scatter_up_to_grey(float t) const;
  // The integral of sigma_s,c T_c over the whole record, per channel.
  RGB scatter_totals() const { return scatter_totals_; }
  // t with pdf sigma_s,c(t) T_c(t) / scatter_totals()[c] in channel c alone (std::nullopt when
  // that channel does not scatter); the returned pdf is that channel's.
  std::optional<DistanceSample> sample_scatter_channel(int c, float u_distance) const;

  // Free-flight sampling for indirect paths: with probability 1 - avg_c T_c(end) returns a
  // collision distance with pdf(t) = avg_c sigma_t,c(t) T_c(t) (NOT renormalised), or a surface
  // layer (DistanceSample::layer) with probability avg_c opacity T_c in front, otherwise
  // std::nullopt (the ray passes the whole record, probability avg_c T_c(end)).
  std::optional<DistanceSample> sample_free_flight(float u_channel, float u_distance) const;
  float free_flight_pdf(float t) const;

 private:
  void append(const MarchStep& coefficients);  // t0, t1, sigma_t, sigma_s and lobe range of the step
  void apply_layer(const SurfaceLayer& layer);
  std::optional<DistanceSample> layer_crossing(float t, int c, double target) const;
  std::vector<MarchStep> steps_;
  std::vector<MarchStep> unlayered_;  // insert_layers' copy of the steps (kept to avoid allocating)
  std::vector<SurfaceLayer> layers_;
  RGB layer_totals_{0.0f};
  std::vector<PhaseLobe> lobes_;
  RGB emission_;
  float holdout_ = 0.0f;
  // Kept up to date by push(): every query reads them, and recomputing them costs three exp
  // and three expm1 in double each time.
  RGB end_transmittance_{1.0f};  // T at the end of the last step
  RGB scatter_totals_{0.0f};     // per-channel integral of sigma_s T over the record
  bool grey_ = true;
};

}  // namespace caligo
