// Per-pixel sums of path samples, split into the AOVs chosen at render time, with each pixel's
// own sample count; resolved into an Image with named EXR layers at the end.
// Sums are exact (FixedSum), so a film is the same bit for bit however its samples were split
// into ranges and merged: a render cut into two sample ranges and merged equals one render.
// Each pixel is written by exactly one tile at a time, so no locking is needed.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "image/image.h"
#include "integrators/path_sample.h"
#include "settings/aov.h"
#include "render/fixed_sum.h"

namespace caligo {

class Film {
 public:
  Film(Vec2i resolution, AovSet aovs);

  // Bytes a film of this shape holds, and what resolving it into an Image adds: what a render
  // needs besides the scene (checked against the machine's memory before rendering).
  static uint64_t memory_estimate(Vec2i resolution, AovSet aovs);

  Vec2i resolution() const { return resolution_; }
  AovSet aovs() const { return aovs_; }

  // One sample of pixel (x, y); `depth` is the camera-space Z of its first visible surface
  // (kInfinity for none). A sample whose radiance is not finite is counted with zero radiance
  // (it would poison the pixel forever; it is a bug to find, not light).
  void add(int x, int y, const PathSample& s, float depth);

  uint32_t sample_count(int x, int y) const { return counts_[index(x, y)]; }

  // The estimated RMSE of the resolved beauty against its converged value: the square root of
  // the mean, over pixels with two samples or more and over R, G, B, of the variance of each
  // pixel's mean. nullopt without Aov::kVariance or without such a pixel.
  std::optional<double> estimated_rmse() const;

  // The estimated relative error of pixel (x, y)'s mean beauty, from its own samples: the root of
  // the variance of its mean, averaged over R, G, B, over its mean averaged likewise (at least
  // kRelativeErrorFloor, so that a near-black pixel is not refined for noise nobody sees).
  // Infinity below two samples or without Aov::kVariance. Adaptive sampling stops by it.
  static constexpr double kRelativeErrorFloor = 1e-3;
  double relative_error(int x, int y) const;

  // Averages over each pixel's own samples (a pixel with none is zero, alpha 0): the beauty as
  // R G B, then A, Z, N.X/Y/Z, albedo.R/G/B and the light layers "surface_direct.R", ... as
  // selected (aov_channels). Z is the nearest depth any sample of the pixel saw.
  Image resolve() const;

  // Adds another film's samples: sums and counts add, depths take the nearer. Exact, so
  // merging is associative and commutative. Throws std::invalid_argument when the resolution
  // or the AOV set differ.
  void merge(const Film& other);

  // The raw sums and counts, written atomically (temporary file, then rename), with a caller's
  // 64-bit key (checkpoints store a hash of scene and settings in it). Throws std::runtime_error
  // naming the file when it cannot be written.
  void save(const std::string& path, uint64_t key = 0) const;
  // Reads a file written by save(). A missing, truncated, foreign or inconsistent file throws
  // InputError naming it. `key`, when given, receives the saved key.
  static Film load(const std::string& path, uint64_t* key = nullptr);

  // The same raw sums and counts in memory, byte for byte what save() writes: for sending a film
  // between processes (src/distributed/ over MPI). from_bytes checks what load() checks and
  // throws InputError naming `source` (e.g. "film from rank 3").
  std::string to_bytes(uint64_t key = 0) const;
  static Film from_bytes(std::string_view bytes, const std::string& source, uint64_t* key = nullptr);

  // What the sampler that renders into this film has learnt from its samples so far (path
  // guiding's field, guiding/guiding_field.h, as bytes): saved and loaded with the sums, so a
  // resumed render continues the training where it stopped. Empty when nothing learns. merge()
  // keeps this film's.
  const std::string& training_state() const { return training_; }
  void set_training_state(std::string bytes) { training_ = std::move(bytes); }

  friend bool operator==(const Film&, const Film&) = default;

 private:
  size_t index(int x, int y) const { return size_t(y) * size_t(resolution_.x) + size_t(x); }

  Vec2i resolution_;
  AovSet aovs_;
  // Summed channels per pixel: beauty RGB, then alpha, normal XYZ, albedo RGB and each light
  // layer's RGB when selected; the offsets of each (-1: not held).
  int channels_ = 3;
  int alpha_ = -1, normal_ = -1, albedo_ = -1, squares_ = -1;  // squares_: sum of beauty^2
  std::array<int, kLightKindCount> light_{};
  std::vector<FixedSum> sums_;  // pixel-major, channels_ per pixel
  std::vector<uint32_t> counts_;
  std::vector<float> depth_;  // nearest depth per pixel (only with Aov::kDepth)
  std::string training_;
};

}  // namespace caligo
