// Volume emission as a light (fire, explosions): points sampled where volume primitives emit, so
// that a vertex near a flame connects to it rather than waiting for a bounce ray to wander in.
//
// The proposal: each emissive primitive (constant emission, blackbody temperature or flame) is a
// lattice of cells -- a grid's occupied 8^3 blocks, or 4^3 cells over an analytic primitive's
// bounds -- each weighted by its estimated emitted power (the mean of the emission's channel
// average at 4^3 points of its non-zero part, 2^3 in fields of over 65,536 cells, times that
// part's world volume); a cell is chosen by that weight and a
// point uniformly inside it. The density per unit world volume is piecewise constant per cell,
// summed over primitives where they overlap.
//
// MIS needs the proposal's density over directions seen from a vertex x: the marginal
//   direction_pdf(x, w) = integral over t > 0 of pdf(x + t w) t^2 dt,
// the density of the sampled point's direction (dV = t^2 dt dw), a sum over the cells the line
// crosses of (t1^3 - t0^3) / 3 times the cell's density (a DDA). Both MIS strategies weigh with
// it (a bounce ray gathers the emission of its whole line, so its weight depends on the
// direction alone). That split is unbiased only if the proposal covers every point that emits:
// so every occupied cell keeps at least 10^-3 of the mean cell weight (the shell of blocks a
// trilinear footprint adds around data reads 0 at the estimate's points, yet emits), and a
// scene with an emissive primitive the sampler cannot cover (unbounded, a singular placement,
// more than kMaxEmissionCells cells in its box) gets no sampler: emission is then left to
// bounce rays alone. Immutable after build; thread-safe to read.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "core/transform.h"

#include "core/rgb.h"
#include "core/vec.h"
#include "volumes/volume_context.h"
#include "volumes/volume_scene.h"

namespace caligo {

inline constexpr int64_t kMaxEmissionCells = int64_t(1) << 24;  // 64 MiB of densities per primitive

struct EmissionPoint {
  Vec3 p;
  float pdf = 0.0f;  // per unit world volume (every primitive's share at p)
};

class EmissionSampler {
 public:
  EmissionSampler() = default;
  // `context`: a lookup context for the build (grid accessors), not kept.
  static EmissionSampler build(const VolumeScene& volumes, VolumeContext& context);

  bool empty() const { return cdf_.empty(); }
  size_t cells() const { return entries_.size(); }
  size_t memory_bytes() const;

  // A point from (u_cell, u): u_cell picks the cell, u the point inside it (all in [0, 1)).
  std::optional<EmissionPoint> sample(float u_cell, Vec3 u) const;
  // The density of sample() at world point p, per unit volume.
  float pdf(Vec3 p) const;
  // The density of sample()'s direction seen from x, per steradian, along unit direction w.
  float direction_pdf(Vec3 x, Vec3 w) const;

  // One primitive's lattice: one unit per cell, the cells at [0, dims) (a grid's block
  // (lo + c) is cell c), mapped affinely to the world.
  struct Field {
    Transform lattice_to_world;
    std::array<int32_t, 3> dims{};
    std::vector<float> density;  // per unit world volume, per cell; 0 where nothing is sampled
    float cell_volume = 0.0f;    // world volume of one cell
  };

 private:
  std::vector<Field> fields_;
  struct Entry {
    uint32_t field;
    uint32_t cell;  // index into the field's dense cell array
  };
  std::vector<Entry> entries_;
  std::vector<float> cdf_;  // inclusive prefix sums of the entries' weights, normalised to end at 1
};

// The emission at p of every volume primitive covering it, per unit length (what a march
// integrates at p), for the sampled point's contribution.
RGB emission_at(const VolumeScene& volumes, Vec3 p, VolumeContext& context);

}  // namespace caligo
