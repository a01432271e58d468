// Within a step [t0, t1) of constant coefficients, channel c has
//   T_c(t) = T_c(t0) exp(-sigma_t,c (t - t0)),
//   integral of sigma_s,c T_c over [t0, t) = sigma_s,c T_c(t0) (1 - exp(-sigma_t,c (t - t0))) / sigma_t,c,
// so both samplers find their step by binary search over the per-step prefix values (T at step
// starts, scatter_before) and invert the exponential inside the step in closed form. Inversions run
// in double: the prefix values are floats, but the within-step solve should not add to their error.
//
// Canonical samples are < 1, so the inversions never aim at the last 2^-24 of a step's mass; this
// keeps sampled points where T_c(t) > 0 and hence every returned pdf positive and finite.
#include "raymarch/transmittance_record.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/math.h"

namespace caligo {
namespace {

constexpr int kChannels = 3;

float& channel(RGB& v, int c) { return c == 0 ? v.r : (c == 1 ? v.g : v.b); }

// sigma_t * length, treating 0 * infinity (a clear channel over an unbounded step) as 0.
double optical_depth(float sigma_t, float length) { return sigma_t > 0.0f ? double(sigma_t) * length : 0.0; }

// Integral of exp(-sigma_t s) over [0, length); expm1 keeps optically thin steps accurate.
double exp_integral(float sigma_t, float length) {
  const double tau = optical_depth(sigma_t, length);
  return tau > 0.0 ? -std::expm1(-tau) / sigma_t : double(length);
}

bool is_grey(RGB v) { return v.r == v.g && v.g == v.b; }

// Grey media (the common case) take one exp instead of three; the values are the same.
RGB transmittance_in_step(const MarchStep& s, float t) {
  RGB out;
  if (is_grey(s.sigma_t)) {
    const double e = std::exp(-optical_depth(s.sigma_t.r, t - s.t0));
    for (int c = 0; c < kChannels; ++c) channel(out, c) = float(s.transmittance[c] * e);
    return out;
  }
  for (int c = 0; c < kChannels; ++c)
    channel(out, c) = float(s.transmittance[c] * std::exp(-optical_depth(s.sigma_t[c], t - s.t0)));
  return out;
}

RGB transmittance_after_step(const MarchStep& s) { return transmittance_in_step(s, s.t1); }

// Integral of sigma_s,c T_c over the whole step, per channel.
RGB scatter_in_step(const MarchStep& s) {
  RGB out;
  const bool one = is_grey(s.sigma_t);
  const double shared = one ? exp_integral(s.sigma_t.r, s.t1 - s.t0) : 0.0;
  for (int c = 0; c < kChannels; ++c)
    channel(out, c) = float(double(s.sigma_s[c]) * s.transmittance[c] *
                            (one ? shared : exp_integral(s.sigma_t[c], s.t1 - s.t0)));
  return out;
}

// Index of the last step with t0 <= t, or -1.
int last_step_starting_by(std::span<const MarchStep> steps, float t) {
  const auto it =
      std::upper_bound(steps.begin(), steps.end(), t, [](float x, const MarchStep& s) { return x < s.t0; });
  return int(it - steps.begin()) - 1;
}

// Keeps a point computed from t0 + offset inside [t0, t1) despite rounding.
float clamp_into_step(const MarchStep& s, double t) {
  return std::clamp(float(t), s.t0, std::nextafter(s.t1, s.t0));
}

// The channel whose slice of [0, sum w) holds x; channels of zero weight have empty slices and
// are never returned (rounding at the top edge falls back to the last channel of positive weight).
int pick_channel(RGB w, float x) {
  int last_positive = 0;
  for (int c = 0; c < kChannels; ++c)
    if (w[c] > 0.0f) last_positive = c;
  float cumulative = 0.0f;
  for (int c = 0; c < kChannels; ++c) {
    if (!(w[c] > 0.0f)) continue;
    cumulative += w[c];
    if (x < cumulative || c == last_positive) return c;
  }
  return last_positive;
}

// The point of step s below which a fraction `fraction` of channel c's scatter integral over the
// step lies: solves 1 - exp(-sigma_t x) = fraction (1 - exp(-sigma_t length)) for x.
float invert_scatter_in_step(const MarchStep& s, int c, double fraction) {
  const float length = s.t1 - s.t0;
  const double tau = optical_depth(s.sigma_t[c], length);
  const double x = tau > 0.0 ? -std::log1p(fraction * std::expm1(-tau)) / s.sigma_t[c] : fraction * length;
  return clamp_into_step(s, double(s.t0) + x);
}

float scatter_density_in_step(const MarchStep& s, float t, float total) {
  const RGB tr = transmittance_in_step(s, t);
  return (s.sigma_s.r * tr.r + s.sigma_s.g * tr.g + s.sigma_s.b * tr.b) / total;
}

float free_flight_density_in_step(const MarchStep& s, float t) {
  return (s.sigma_t * transmittance_in_step(s, t)).average();
}

}  // namespace

void TransmittanceRecord::clear() {
  steps_.clear();
  lobes_.clear();
  emission_ = RGB();
  holdout_ = 0.0f;
  end_transmittance_ = RGB(1.0f);
  scatter_totals_ = RGB(0.0f);
  grey_ = true;
  layers_.clear();
  layer_totals_ = RGB(0.0f);
}

// A start that overlaps the previous step by rounding only (a marcher computing step ends as
// t0 + dt * i) is moved to the previous end; a real overlap would break the binary searches and
// is an error. Zero-length steps carry no optical depth and are dropped, so no two steps start at
// one t.
void TransmittanceRecord::push(float t0, float t1, RGB sigma_t, RGB sigma_s,
                               std::span<const PhaseLobe> lobes) {
  if (!steps_.empty() && t0 < steps_.back().t1) {
    const float previous_end = steps_.back().t1;
    if (previous_end - t0 > 1e-5f * std::max(1.0f, std::abs(previous_end)))
      throw std::logic_error("TransmittanceRecord::push: steps must be pushed front to back without overlap");
    t0 = previous_end;
  }
  if (!(t1 > t0)) return;
  const MarchStep step{t0, t1, sigma_t, sigma_s, {}, {}, uint32_t(lobes_.size()), uint32_t(lobes.size())};
  lobes_.insert(lobes_.end(), lobes.begin(), lobes.end());
  append(step);
}

void TransmittanceRecord::append(const MarchStep& coefficients) {
  MarchStep step = coefficients;
  step.transmittance = end_transmittance_;
  step.scatter_before = scatter_totals_;
  steps_.push_back(step);
  end_transmittance_ = transmittance_after_step(step);
  scatter_totals_ = step.scatter_before + scatter_in_step(step);
  grey_ = grey_ && is_grey(step.sigma_t) && is_grey(step.sigma_s);
}

void TransmittanceRecord::apply_layer(const SurfaceLayer& layer) {
  const float opacity = std::clamp(layer.opacity, 0.0f, 1.0f);
  layers_.push_back({layer.t, opacity, end_transmittance_});
  layer_totals_ += end_transmittance_ * opacity;
  end_transmittance_ *= 1.0f - opacity;
}

// The steps are pushed again with the layers between them: a step restarts at each layer inside
// it (same coefficients and lobes), and a layer outside every step starts a step of vacuum up to
// the next step (or a step of one ulp past the end), so that every layer sits at a step start and
// the step in front of it ends with T before the layer.
void TransmittanceRecord::insert_layers(std::span<const SurfaceLayer> layers) {
  if (layers.empty()) return;
  unlayered_.swap(steps_);
  steps_.clear();
  end_transmittance_ = RGB(1.0f);
  scatter_totals_ = RGB(0.0f);
  grey_ = true;
  size_t next = 0;
  const auto vacuum_from = [&](float t0, float t1) {
    MarchStep v{t0, t1, RGB(0.0f), RGB(0.0f), {}, {}, 0, 0};
    append(v);
  };
  for (const MarchStep& s : unlayered_) {
    // Layers in the gap before this step (or at its start).
    while (next < layers.size() && layers[next].t <= s.t0) {
      apply_layer(layers[next]);
      const float t = layers[next++].t;
      const float end = next < layers.size() ? std::min(layers[next].t, s.t0) : s.t0;
      if (end > t) vacuum_from(t, end);
    }
    MarchStep piece = s;
    while (next < layers.size() && layers[next].t < s.t1) {
      piece.t1 = layers[next].t;
      if (piece.t1 > piece.t0) append(piece);
      apply_layer(layers[next++]);
      piece.t0 = piece.t1;
      piece.t1 = s.t1;
    }
    if (piece.t1 > piece.t0) append(piece);
  }
  while (next < layers.size()) {
    apply_layer(layers[next]);
    const float t = layers[next++].t;
    if (next == layers.size() || layers[next].t > t) vacuum_from(t, std::nextafter(t, kInfinity));
  }
}

std::optional<DistanceSample> TransmittanceRecord::sample_layer(int c, float u) const {
  const float total = c < 0 ? layer_totals_.average() : layer_totals_[c];
  if (!(total > 0.0f)) return std::nullopt;
  const float target = u * total;
  float cumulative = 0.0f;
  int last = -1;
  for (size_t i = 0; i < layers_.size(); ++i) {
    const float mass = (c < 0 ? layers_[i].before.average() : layers_[i].before[c]) * layers_[i].opacity;
    if (!(mass > 0.0f)) continue;
    last = int(i);
    cumulative += mass;
    if (target < cumulative) break;
  }
  const SurfaceLayer& l = layers_[size_t(last)];
  const float mass = (c < 0 ? l.before.average() : l.before[c]) * l.opacity;
  return DistanceSample{l.t, mass / total, find_step(l.t), last};
}

std::span<const PhaseLobe> TransmittanceRecord::lobes(const MarchStep& step) const {
  return std::span<const PhaseLobe>(lobes_).subspan(step.first_lobe, step.lobe_count);
}

float TransmittanceRecord::t_begin() const { return steps_.empty() ? 0.0f : steps_.front().t0; }
float TransmittanceRecord::t_end() const { return steps_.empty() ? 0.0f : steps_.back().t1; }

int TransmittanceRecord::find_step(float t) const {
  const int i = last_step_starting_by(steps_, t);
  return i >= 0 && t < steps_[i].t1 ? i : -1;
}

RGB TransmittanceRecord::transmittance(float t) const {
  const int i = last_step_starting_by(steps_, t);
  if (i < 0) return RGB(1.0f);
  const MarchStep& s = steps_[i];
  if (t < s.t1) return transmittance_in_step(s, t);
  // In the gap after step i (vacuum) or past the end: the next step's stored start value, which is
  // exactly what push computed, so T is continuous and consistent with the samplers. A layer may
  // start the next step (its T is after the layer): the gap in front of it has T before.
  if (!layers_.empty() || size_t(i) + 1 == steps_.size()) return transmittance_after_step(s);
  return steps_[i + 1].transmittance;
}

RGB TransmittanceRecord::transmittance_end() const { return end_transmittance_; }

float TransmittanceRecord::scatter_weight_total() const { return scatter_totals_.average(); }

float TransmittanceRecord::scatter_up_to_grey(float t) const {
  const int i = last_step_starting_by(steps_, t);
  if (i < 0) return 0.0f;
  const MarchStep& s = steps_[i];
  const float to = std::min(t, s.t1);
  return s.scatter_before.r + float(double(s.sigma_s.r) * s.transmittance.r * exp_integral(s.sigma_t.r, to - s.t0));
}

std::optional<DistanceSample> TransmittanceRecord::sample_scatter_density(float u_channel,
                                                                          float u_distance) const {
  const RGB w = scatter_totals_;
  const float total = w.r + w.g + w.b;
  if (!(total > 0.0f)) return std::nullopt;
  const int c = pick_channel(w, u_channel * total);
  const auto sample = sample_scatter_channel(c, u_distance);
  if (!sample) return std::nullopt;
  return DistanceSample{sample->t, scatter_density_in_step(steps_[size_t(sample->step)], sample->t, total),
                        sample->step};
}

std::optional<DistanceSample> TransmittanceRecord::sample_scatter_channel(int c, float u_distance) const {
  const RGB w = scatter_totals_;
  if (!(w[c] > 0.0f)) return std::nullopt;
  // Strictly below W_c, so the step found below has a positive share of channel c's integral.
  const float target = std::min(u_distance * w[c], std::nextafter(w[c], 0.0f));
  const auto it = std::partition_point(steps_.begin(), steps_.end(),
                                       [&](const MarchStep& s) { return s.scatter_before[c] <= target; });
  const int i = int(it - steps_.begin()) - 1;  // >= 0: the first step's scatter_before is 0
  const MarchStep& s = steps_[i];
  const double fraction = (double(target) - s.scatter_before[c]) / scatter_in_step(s)[c];
  const float t = invert_scatter_in_step(s, c, std::clamp(fraction, 0.0, double(kOneMinusEpsilon)));
  return DistanceSample{t, float(double(s.sigma_s[c]) * transmittance_in_step(s, t)[c] / w[c]), i};
}

float TransmittanceRecord::scatter_density_pdf(float t) const {
  const int i = find_step(t);
  if (i < 0) return 0.0f;
  const RGB w = scatter_totals_;
  const float total = w.r + w.g + w.b;
  return total > 0.0f ? scatter_density_in_step(steps_[i], t, total) : 0.0f;
}

std::optional<DistanceSample> TransmittanceRecord::sample_free_flight(float u_channel,
                                                                      float u_distance) const {
  if (steps_.empty()) return std::nullopt;
  const int c = std::min(int(u_channel * kChannels), kChannels - 1);
  // The collision is where T_c falls to 1 - u, i.e. at optical depth -log(1 - u).
  const double target = 1.0 - double(u_distance);
  if (transmittance_end()[c] >= target) return std::nullopt;  // passes the whole record
  const auto it = std::partition_point(steps_.begin(), steps_.end(),
                                       [&](const MarchStep& s) { return s.transmittance[c] >= target; });
  const int i = int(it - steps_.begin()) - 1;  // >= 0: the first step starts at T = 1
  const MarchStep& s = steps_[i];
  if (!layers_.empty() && transmittance_after_step(s)[c] >= target) return layer_crossing(steps_[i + 1].t0, c, target);
  // T_c crosses the target inside step i (T is constant over gaps), so sigma_t,c > 0 there.
  const double x = (std::log(double(s.transmittance[c])) - std::log(target)) / s.sigma_t[c];
  const float t = clamp_into_step(s, double(s.t0) + std::max(x, 0.0));
  return DistanceSample{t, free_flight_density_in_step(s, t), i};
}

// T_c falls past `target` in the jump of the layers at t (several when coincident): the first whose
// factor takes it below.
std::optional<DistanceSample> TransmittanceRecord::layer_crossing(float t, int c, double target) const {
  const auto first = std::partition_point(layers_.begin(), layers_.end(), [&](const SurfaceLayer& l) { return l.t < t; });
  for (auto it = first; it != layers_.end() && it->t == t; ++it)
    if (double(it->before[c]) * (1.0 - it->opacity) < target || std::next(it) == layers_.end() || std::next(it)->t != t)
      return DistanceSample{t, (it->before * it->opacity).average(), find_step(t), int(it - layers_.begin())};
  return std::nullopt;  // unreachable: a jump holds the target only where a layer is
}

float TransmittanceRecord::free_flight_pdf(float t) const {
  const int i = find_step(t);
  return i < 0 ? 0.0f : free_flight_density_in_step(steps_[i], t);
}

}  // namespace caligo
