// Test-only: production (path_tracer.h) held against the reference ladder's delta tracking
// (reference.h) by image means. Both sides' standard errors come from their own samples (per
// pixel, so the image mean's variance is the sum of the pixels' variances of their means).
#pragma once

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/parallel.h"
#include "core/rng.h"
#include "integrators/path_tracer.h"
#include "integrators/reference.h"
#include "scene/scene.h"

namespace caligo::testing {


struct MeanEstimate {
  RGB mean;
  RGB std_error;  // of the mean, per channel
  float average_std_error = 0.0f;  // of the channel average
  double seconds = 0.0;
};

// Per-pixel sums of samples, their squares, and of the channel average's squares.
struct PixelMoments {
  double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0}, avg_sum2 = 0;
  void add(RGB v) {
    for (int c = 0; c < 3; ++c) sum[c] += v[c], sum2[c] += double(v[c]) * v[c];
    avg_sum2 += double(v.average()) * v.average();
  }
};

template <typename Sample>
inline MeanEstimate image_mean(const Scene& scene, int spp, Sample&& sample) {
  const auto start = std::chrono::steady_clock::now();
  const Vec2i res = scene.desc().camera.resolution;
  const Camera camera = scene.camera(res);
  std::vector<PixelMoments> pixels(size_t(res.x) * size_t(res.y));
  parallel_for(res.y, [&](int y) {
    for (int x = 0; x < res.x; ++x)
      for (int s = 0; s < spp; ++s) pixels[size_t(y) * size_t(res.x) + size_t(x)].add(sample(camera, x, y, s));
  });
  // Var(image mean) = sum over pixels of Var(pixel mean) / P^2, each from its own samples.
  double mean[3] = {0, 0, 0}, var[3] = {0, 0, 0}, avg_var = 0;
  const double n = spp, p = double(pixels.size());
  for (const PixelMoments& m : pixels) {
    double avg_mean = 0;
    for (int c = 0; c < 3; ++c) {
      const double mu = m.sum[c] / n;
      mean[c] += mu / p;
      var[c] += (m.sum2[c] / n - mu * mu) / (n - 1) / (p * p);
      avg_mean += mu / 3;
    }
    avg_var += (m.avg_sum2 / n - avg_mean * avg_mean) / (n - 1) / (p * p);
  }
  MeanEstimate e;
  e.mean = RGB(float(mean[0]), float(mean[1]), float(mean[2]));
  e.std_error = RGB(float(std::sqrt(var[0])), float(std::sqrt(var[1])), float(std::sqrt(var[2])));
  e.average_std_error = float(std::sqrt(avg_var));
  e.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return e;
}

struct Limits {
  PathLimits path{.max_bounces = 16, .max_volume_bounces = 256};  // production's and the ladder's
  bool absorption_by_weight = true;
};

inline MeanEstimate production_mean(const Scene& scene, int spp, Limits limits, uint64_t seed = 1) {
  PathSettings settings = scene.desc().render.path;  // its priority_shadows
  settings.absorption_by_weight = limits.absorption_by_weight;
  settings.limits = limits.path;
  return image_mean(scene, spp, [&](const Camera& camera, int x, int y, int s) {
    thread_local PathScratch scratch;
    PathCounters counters;
    const Sampler sampler(seed, {x, y}, uint32_t(s));
    const Vec2 jitter = sampler.get_2d(sample_dim::kFilm);
    const Ray ray = camera.generate_ray({float(x) + jitter.x, float(y) + jitter.y});
    const RGB v = trace_path(scene, ray, sampler, settings, counters, scratch).beauty();
    return v.is_finite() ? v : RGB(0.0f);  // as the film does
  });
}

inline MeanEstimate ladder_mean(const Scene& scene, int spp, Limits limits, uint64_t seed = 2) {
  return image_mean(scene, spp, [&](const Camera& camera, int x, int y, int s) {
    Pcg32 rng(hash_values(seed, uint64_t(x), uint64_t(y)), uint64_t(s));
    const Vec2 jitter{rng.next_float(), rng.next_float()};
    const Ray ray = camera.generate_ray({float(x) + jitter.x, float(y) + jitter.y});
    return reference_delta_tracking(scene, ray, limits.path, rng);
  });
}

inline std::string str(RGB c) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.5f %.5f %.5f)", double(c.r), double(c.g), double(c.b));
  return buf;
}

// The channel averages of the two image means agree within 4 combined standard errors
// (measured 2026-12: 0.07 to 1.25 of them on these seven scenes), and 4 standard errors must be
// at most 1 % of the mean (else the sample counts are too small to see a 1 % bias).
inline void expect_agree(const Scene& scene, int production_spp, int ladder_spp, Limits limits, const std::string& what) {
  const MeanEstimate prod = production_mean(scene, production_spp, limits);
  const MeanEstimate ref = ladder_mean(scene, ladder_spp, limits);
  const float a = prod.mean.average(), b = ref.mean.average();
  const float combined = std::hypot(prod.average_std_error, ref.average_std_error);
  const float tolerance = 4.0f * combined;
  std::printf(
      "  [%s]\n    production %s avg %.5f +- %.5f (%.2f%%) %d spp %.1fs\n"
      "    ladder     %s avg %.5f +- %.5f (%.2f%%) %d spp %.1fs\n"
      "    difference %.5f = %.2f%% of the mean = %.2f combined standard errors (%.2f%%)\n",
      what.c_str(), str(prod.mean).c_str(), double(a), double(prod.average_std_error),
      100.0 * prod.average_std_error / a, production_spp, prod.seconds, str(ref.mean).c_str(), double(b),
      double(ref.average_std_error), 100.0 * ref.average_std_error / b, ladder_spp, ref.seconds, double(a - b),
      100.0 * (a - b) / b, double((a - b) / combined), 100.0 * combined / b);
  for (int c = 0; c < 3; ++c)
    std::printf("    channel %d: %.5f +- %.5f vs %.5f +- %.5f (%+.2f%%)\n", c, double(prod.mean[c]),
                double(prod.std_error[c]), double(ref.mean[c]), double(ref.std_error[c]),
                100.0 * (prod.mean[c] - ref.mean[c]) / ref.mean[c]);
  EXPECT_LE(tolerance, 0.01f * b) << what << ": too few samples to see a 1% bias";
  EXPECT_LE(std::abs(a - b), tolerance) << what;
}

}  // namespace caligo::testing
